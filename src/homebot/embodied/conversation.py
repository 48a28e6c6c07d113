"""Talking through the body: the robot's voice out of its speaker, answers from its microphone.

``say`` synthesises the text (espeak-ng, the ``speech`` extra) and plays it on the body's
speaker; the body's clock runs while it sounds. ``listen`` lets the body tick while the
microphone fills, until an utterance has ended (``_END_OF_TURN`` seconds of quiet after
speech) or nobody has begun within ``_WAIT`` seconds, and hears it in a dialogue state
(``homebot.speech.answers``). ``ask`` asks, listens and, when nobody answers or the answer
is off the point, says so and asks once more. A name, a drink or an open answer is
confirmed ("Did you say John?"); on a "no" the robot asks again (up to three times in
all) and hears the answer as anything but what was denied. Nothing here knows who is in
the home: what was said comes only through the microphone.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from homebot.errors import PartMissing, SpeechError
from homebot.events import EventLog
from homebot.robot import Body

if TYPE_CHECKING:
    from homebot.speech.answers import AnswerRecognizer
    from homebot.speech.recognizer import Hearing

__all__ = ["Conversation"]

_WAIT = 6.0  #: seconds the robot waits for someone to begin answering
_LONGEST_ANSWER = 12.0  #: seconds of answer the robot listens to at most
_END_OF_TURN = 0.9  #: seconds of quiet after speech that end an answer
_LISTEN_STEP = 0.25  #: seconds the body ticks between looks at what the microphone heard
_ATTEMPTS = 2  #: a question is asked at most twice
_ATTEMPTS_WHEN_CORRECTED = 3  #: ... or thrice when the person said it was misheard
_YES = {"yes", "yeah", "sure", "of", "correct", "that", "right"}  #: first words of a yes
#: dialogue states whose answers the robot confirms ("Did you say John?"): a misheard name
#: or wish comes back as a "no", and the question is asked again
_CONFIRMED = {"name", "drink", "open"}


class Conversation:
    """The robot's voice and ears on ``body``.

    Args:
        body: the speaker and the microphone.
        events: where what was said and heard is recorded.
        recogniser: builds the answer recogniser on first use (building it takes seconds).
    """

    def __init__(self, body: Body, events: EventLog,
                 recogniser: Callable[[], AnswerRecognizer]) -> None:
        self.body = body
        self.events = events
        self._make_recogniser = recogniser
        self._recogniser: AnswerRecognizer | None = None
        self._overheard: list[np.ndarray] = []  #: what the microphone gave since the last word
        #: when the robot last stopped speaking, if it has not listened since: what the
        #: microphone heard after that may be an answer begun before it listened
        self._stopped_speaking: float | None = None

    def say(self, text: str) -> bool:
        """Speak ``text`` aloud; False when the body has no speaker or no voice."""
        try:
            speaker = self.body.speaker()
            from homebot.speech.audio import SAMPLE_RATE, resample
            from homebot.speech.voice import espeak

            samples = espeak().synthesise(text)
        except (PartMissing, ImportError, SpeechError):
            self.events.record("robot.unspoken", text=text)
            return False
        speaker.play(resample(samples, SAMPLE_RATE, speaker.rate), text=text)
        self._stopped_speaking = self.body.now()
        return True

    def ask(self, question: str, state: str) -> str | None:
        """Ask ``question`` and hear the answer in ``state``; once more after silence, an
        answer off the point, or one the person says the robot misheard; None when there
        is still no answer."""
        denied: list[str] = []
        attempt, attempts = 0, _ATTEMPTS
        while attempt < attempts:
            attempt += 1
            if not self.say(question):
                return None
            heard = self.listen(state, denied=tuple(denied))
            if heard.text is None:
                if attempt < attempts and heard.reason != "no_speech":
                    self.say("Sorry, I did not understand.")
                continue
            if state not in _CONFIRMED or self._confirmed(heard.text):
                return heard.text
            denied.append(heard.text)
            # someone who answers and corrects the robot is worth one more try
            attempts = _ATTEMPTS_WHEN_CORRECTED
            if attempt < attempts:
                self.say("Sorry, I misheard.")
        return None

    def _confirmed(self, answer: str) -> bool:
        """Ask whether ``answer`` is what was said: False on a "no" (or an answer not
        understood); True on a yes, and when nobody objects."""
        if not self.say(f"Did you say {answer}?"):
            return True
        heard = self.listen("yes_no")
        return heard.reason == "no_speech" or _is_yes(heard)

    def agreed(self) -> bool:
        """Listen for the answer to a request just made: whether it was a yes."""
        return _is_yes(self.listen("yes_no"))

    def listen(self, state: str, denied: tuple[str, ...] = ()) -> Hearing:
        """What the microphone hears next, as one answer in ``state``, not one of the
        answers ``denied`` (the person said the robot misheard them)."""
        from homebot.speech.audio import SAMPLE_RATE, resample
        from homebot.speech.recognizer import Hearing

        try:
            microphone = self.body.microphone()
            recogniser = self._ears()
        except (PartMissing, ImportError, SpeechError):
            return Hearing(None, "no_microphone", state)
        # What was heard before is the robot's own voice, and no answer to it; but what
        # came after the robot stopped speaking may be one begun while it looked round for
        # whom it asked, and is kept.
        before = microphone.read()
        since = 0.0 if self._stopped_speaking is None else \
            self.body.now() - self._stopped_speaking
        self._stopped_speaking = None
        kept = min(round(min(since, _WAIT) * microphone.rate), before.size)
        chunks: list[np.ndarray] = [resample(before[before.size - kept:], microphone.rate,
                                             SAMPLE_RATE)] if kept > 0 else []
        waited = 0.0
        ticks = max(1, round(_LISTEN_STEP / self.body.tick_period))
        while waited < _WAIT + _LONGEST_ANSWER:
            self.body.tick(ticks)
            waited += ticks * self.body.tick_period
            chunks.append(resample(microphone.read(), microphone.rate, SAMPLE_RATE))
            audio = np.concatenate(chunks)
            utterances = recogniser.segmenter.utterances(audio)
            if not utterances and waited >= _WAIT:
                break
            if utterances and audio.size - utterances[-1].end >= _END_OF_TURN * SAMPLE_RATE:
                break
        heard = recogniser.hear(audio, state, denied=denied)
        self.events.record("robot.heard", text=heard.text, state=state, reason=heard.reason)
        return heard

    def start_overhearing(self) -> None:
        """Forget what the microphone heard so far (before ``overheard`` calls)."""
        with contextlib.suppress(PartMissing):
            self.body.microphone().read()
        self._overheard = []

    def overheard(self, state: str) -> Hearing | None:
        """Without waiting: what someone finished saying since the last call, heard in
        ``state`` (None: nobody finished saying anything). For words said while the robot
        does something else, as "stop" while it follows someone."""
        from homebot.speech.audio import SAMPLE_RATE, resample

        try:
            microphone = self.body.microphone()
            recogniser = self._ears()
        except (PartMissing, ImportError, SpeechError):
            return None
        self._overheard.append(resample(microphone.read(), microphone.rate, SAMPLE_RATE))
        audio = np.concatenate(self._overheard)
        utterances = recogniser.segmenter.utterances(audio)
        if not utterances:
            # keep only a little quiet before whatever comes next
            self._overheard = [audio[-round(_END_OF_TURN * SAMPLE_RATE):]]
            return None
        if audio.size - utterances[-1].end < _END_OF_TURN * SAMPLE_RATE and \
                audio.size < _LONGEST_ANSWER * SAMPLE_RATE:
            return None  # still speaking
        self._overheard = []
        heard = recogniser.hear(audio, state)
        self.events.record("robot.heard", text=heard.text, state=state, reason=heard.reason)
        return heard

    def _ears(self) -> AnswerRecognizer:
        if self._recogniser is None:
            self._recogniser = self._make_recogniser()
        return self._recogniser


def _is_yes(heard: Hearing) -> bool:
    """Whether what was heard (in the yes/no state) is a yes."""
    return heard.text is not None and heard.text.split()[0] in _YES
