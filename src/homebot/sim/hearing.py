"""People in the simulated home hear the robot and answer aloud.

Everything the robot's speaker plays goes into the ``AudioScene`` with its text. The
people within earshot (``EARSHOT`` metres of the robot, in its room or not further than
``THROUGH_A_DOOR``) hear it; the one it names, else the nearest, takes it as said to
them. The simulator understands English for them (it has the text) and has them:

- answer a question (a sentence with a question mark) with ``simulation.responder``,
  aloud, after a human pause: the answer is synthesised with the voice the wiring gives
  (``PersonVoice``) and put into the scene, where the robot's microphone hears it. Someone
  the responder gives no answer for stays silent.
- take what the robot holds out to them ("here is your cup": ``homebot.sim.hands`` has them
  pull at it), and put what they hold into its open hand when asked ("please put the cup
  in my hand");
- do what they are asked, if they are cooperative: open a door the request names, step
  off the robot's way ("let me through", "step aside"), come along behind the robot
  ("follow me": they walk after it by their own rule, ``homebot.sim.guided``, until it
  asks or hands them something else; one who wandered off follows again when asked from
  near) or go
  ahead to a room it names ("go ahead to the kitchen": they walk there at their own pace,
  ``homebot.sim.routes``); and say "yes, sure" or "no, sorry".
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable

import numpy as np

from homebot.sim.audio import AudioScene, Sound
from homebot.sim.guided import GuidedWalk, Personality, personality_of
from homebot.sim.routes import RouteWalk, plan_route
from homebot.sim.simulation import Simulation
from homebot.text import fold
from homebot.world import DoorState

__all__ = ["EARSHOT", "PeopleHearing", "PersonVoice"]

#: A person's voice: (their name, what they say) -> 16 kHz int16 samples.
PersonVoice = Callable[[str, str], np.ndarray]

EARSHOT = 3.5  #: metres within which a person hears the robot in its room
THROUGH_A_DOOR = 1.5  #: metres within which a person in another room hears it
_PAUSE = 0.6  #: seconds between the robot's last word and the person's first
_GOING_AHEAD_PACE = (0.3, 0.45)  #: m/s: someone sent ahead walks slowly, to be followed
_STEPPING_PACE = 0.7  #: m/s: someone stepping off the robot's way
_STEP_ASIDE = ("let me through", "let me pass", "let me by", "step aside", "make way")
_COME_ALONG = ("follow me",)
_HERE_IS = ("here is", "here are", "here you are", "here you go", "this is for you")
_GO_AHEAD = re.compile(r"go ahead to (?:the )?(.+?)(?:,|\.|$)")
_LEAD = ("i will follow you",)  #: "go ahead, I will follow you": they go where they wish
_ARRIVED = "We are here."  #: what someone the robot followed says on arriving
_YES, _NO = "Yes, sure.", "No, sorry."
_DID_YOU_SAY = re.compile(r"\s*did you say (.+?)\s*\?*\s*$")
#: words that frame an answer without carrying it ("my name is", "i said", "a")
_FRAME_WORDS = {"my", "name", "is", "i", "am", "i'm", "it", "it's", "call", "me", "said",
                "a", "an", "some", "the", "please", "thank", "you", "would", "like", "from",
                "come", "want", "years", "old", "favourite", "say"}


class PeopleHearing:
    """The people of ``simulation`` listening to the robot (see the module docstring).

    Args:
        simulation: the truth: people, doors, how they answer.
        audio: the home's sounds, where the robot's voice is and the answers go.
        voice: how each person sounds; None: people hear but cannot answer aloud.
        walk: sets someone walking a route of their own, or after the robot
            (``PeopleWalking.walk_route``); None: people asked to go somewhere, or to
            follow, stay where they are.
    """

    def __init__(self, simulation: Simulation, audio: AudioScene,
                 voice: PersonVoice | None,
                 walk: Callable[[RouteWalk | GuidedWalk], None] | None = None) -> None:
        self.sim = simulation
        self.audio = audio
        self.voice = voice
        self._walk = walk
        #: who comes along behind the robot (asked to "follow me"), and how they walk
        self.coming_along: str | None = None
        self.guided: GuidedWalk | None = None
        #: how someone guided follows, by name (a trial's choice; default ``personality_of``)
        self.personalities: dict[str, Personality] = {}
        #: who was asked to put something in the robot's hand, and what ("please put the
        #: cup in my hand"); ``homebot.sim.hands`` has them do it
        self.asked_to_give: tuple[str, str] | None = None
        #: who is handed something ("here is your cup"): they take it when held out
        self.asked_to_take: str | None = None
        #: what each person was last asked and answered (a question asked again, "did you
        #: say ...?")
        self._last: dict[str, tuple[str, str]] = {}

    # ------------------------------------------------------------ hearing

    def robot_said(self, sound: Sound) -> None:
        """The robot said ``sound.text``: whoever it is meant for reacts."""
        text = fold(sound.text or "")
        listener = self._listener(text)
        if listener is None:
            return
        model = self.sim.people[listener].model
        self.sim.events.record("sim.heard", person=listener, text=sound.text)
        if listener == self.coming_along and not _says(text, _COME_ALONG) and (
                "?" in text or "in my hand" in text or _says(text, _HERE_IS)
                or self._is_request(text)):
            self._end_guided_walk()  # asked or handed something else: the walk is over
        reply: str | None
        if "in my hand" in text:
            named = [obj for obj in self.sim.world.objects if fold(obj) in text]
            self.asked_to_give = (listener, max(named, key=len) if named else "")
            return
        if _says(text, _HERE_IS):
            self.asked_to_take = listener
            return
        request = self._is_request(text)
        if "?" in text and not request:
            question = _without_address(text, listener)
            reply = self._answer(listener, question)
        elif request:
            reply = _YES if model.cooperative and self._do(listener, text) else _NO
        elif _says(text, _COME_ALONG):
            reply = self._come_along(listener, text)
        else:
            return
        if reply:
            self._say(listener, reply, sound.end + _PAUSE)

    def _answer(self, person: str, question: str) -> str | None:
        """What ``person`` answers to ``question``: the responder's answer, their name at
        times in a sentence ("My name is John."), an answer asked for again at times as
        "I said ..." (seeded); to "did you say ...?" after answering, whether the robot
        repeated the words of their answer ("Yes." or "No.")."""
        model = self.sim.people[person].model
        asked = _DID_YOU_SAY.match(question)
        last = self._last.get(person)
        if asked is not None and last is not None:
            return "Yes." if _content(asked.group(1)) == _content(last[1]) else "No."
        reply = self.sim.responder(model, question)
        if not reply:
            return reply
        forms = [reply]
        if fold(reply) == fold(person):
            forms += [f"My name is {reply}.", f"I am {reply}."]
        elif last is not None and last[0] == fold(question):
            forms += [f"I said {reply}."]
        self._last[person] = (fold(question), reply)
        choice = np.random.default_rng([self.sim.seed, len(self.audio.sounds)])
        return forms[int(choice.integers(len(forms)))]

    def _come_along(self, person: str, text: str) -> str | None:
        """``person`` was asked to follow the robot (in ``text``): they set off after it
        (``GuidedWalk``), or, already following, go on; one who wandered off follows again
        only when asked from near (from farther they do not answer), and nobody follows
        when asked by someone else's name. Their answer."""
        sim = self.sim
        named = [name for name in sim.people if re.search(rf"\b{re.escape(fold(name))}\b", text)]
        if named and person not in named:
            return None
        if not sim.people[person].model.cooperative:
            return _NO
        walk = self.guided
        if walk is not None and not walk.finished and walk.name == person:
            return _YES if walk.asked_again(sim) else None
        self._end_guided_walk()
        self.coming_along = person
        if self._walk is not None:
            personality = self.personalities.get(person) or personality_of(sim.seed, person)
            self.guided = GuidedWalk.start(sim, person, personality)
            self._walk(self.guided)
            sim.events.record("sim.person", person=person, did="follows",
                              personality=personality.value)
        return _YES

    def _end_guided_walk(self) -> None:
        if self.guided is not None:
            self.guided.finished = True
        self.guided = self.coming_along = None

    def _listener(self, text: str) -> str | None:
        """Who takes ``text`` as said to them: the person named among those who hear it,
        else the nearest who does; None: nobody hears it."""
        sim = self.sim
        here = sim.robot_pose[:2]
        room = sim.robot_room()
        hearing = sorted((math.dist(here, state.position), name)
                         for name, state in sim.people.items()
                         if math.dist(here, state.position) <= (
                             EARSHOT if state.room == room else THROUGH_A_DOOR))
        named = [name for _, name in hearing if re.search(rf"\b{re.escape(fold(name))}\b", text)]
        if named:
            return named[0]
        return hearing[0][1] if hearing else None

    # ------------------------------------------------------------ requests

    def _is_request(self, text: str) -> bool:
        return (self._door_named(text) is not None and "open" in text) or \
            _says(text, _STEP_ASIDE) or _GO_AHEAD.search(text) is not None or \
            _says(text, _LEAD)

    def _door_named(self, text: str) -> str | None:
        named = [door for door in self.sim.door_state if fold(door) in text]
        return max(named, key=len) if named else None

    def _do(self, person: str, text: str) -> bool:
        """Do what the robot asked; whether it is done."""
        sim = self.sim
        door = self._door_named(text)
        if door is not None and "open" in text:
            if sim.door_state[door] is DoorState.LOCKED:
                return False
            sim.open_wide(door)
            sim.events.record("sim.person", person=person, did="opened", door=door)
            return True
        ahead = _GO_AHEAD.search(text)
        if ahead is not None or _says(text, _LEAD):
            return self._lead(person, None if ahead is None else ahead.group(1))
        # asked to let the robot by: off its way, or out of the doorway they stand in
        if not self._step_aside(person):
            return False
        sim.events.record("sim.person", person=person, did="stepped aside")
        return True

    def _step_aside(self, person: str) -> bool:
        """``person`` walks off the robot's way (``Simulation.spot_aside``), or out of the
        doorway they block into their room; whether they set off. Without walking
        (``walk`` None) they are put there."""
        sim = self.sim
        state = sim.people[person]
        if self._walk is None:
            return sim.step_aside(person, state.blocking_door)
        spot = sim.spot_aside(state.position)
        if spot is None and state.blocking_door is not None:
            spot = sim.free_floor_in(state.room)
        route = None if spot is None else plan_route(sim, state.position, [spot])
        if route is None:
            return False
        self._walk(RouteWalk(person, route, _STEPPING_PACE, pause_chance=0.0, seed=sim.seed))
        return True

    def _lead(self, person: str, room_words: str | None) -> bool:
        """``person`` walks ahead, at their own pace, to the room named (else to a place
        of their own choosing), and says they are there on arriving; whether they set off."""
        sim = self.sim
        if self._walk is None:
            return False
        choice = np.random.default_rng([sim.seed, len(self.audio.sounds)])
        if room_words is None:
            here = sim.people[person].room
            rooms = sorted(room for room in sim.world.room_polygons if room != here)
            if not rooms:
                return False
            room: str | None = rooms[int(choice.integers(len(rooms)))]
        else:
            room = next((name for name in sim.world.room_polygons
                         if fold(name) == room_words), None)
        if room is None:
            return False
        route = plan_route(sim, sim.people[person].position, [sim.free_floor_in(room)])
        if route is None:
            return False
        # they set off once they have answered
        self._walk(RouteWalk(person, route, float(choice.uniform(*_GOING_AHEAD_PACE)),
                             starts_at=sim.clock.now() + 2.0, seed=sim.seed,
                             at_end=lambda: self.say(person, _ARRIVED)))
        return True

    # ------------------------------------------------------------ speaking

    def say(self, person: str, text: str) -> None:
        """``person`` says ``text`` aloud now (an operator telling the robot to stop)."""
        self._say(person, text, self.sim.clock.now())

    def _say(self, person: str, text: str, start: float) -> None:
        self.sim.events.record("sim.person_said", person=person, text=text)
        if self.voice is None:
            return
        self.audio.emit(self.voice(person, text), source=person, text=text, start=start)


def _content(text: str) -> set[str]:
    """The words of an answer that carry it ("my name is john" -> {"john"})."""
    return set(re.findall(r"[\w']+", fold(text))) - _FRAME_WORDS


def _says(text: str, phrases: tuple[str, ...]) -> bool:
    """Whether ``text`` says one of ``phrases`` as words ("where are you from?" does not
    say "here are")."""
    return any(re.search(rf"\b{re.escape(phrase)}\b", text) for phrase in phrases)


def _without_address(text: str, person: str) -> str:
    """The question without the name it was addressed with ("maria, what is ...")."""
    return re.sub(rf"^\s*{re.escape(fold(person))}\s*,?\s*", "", text).strip()
