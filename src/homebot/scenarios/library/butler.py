"""The butler who knows your preferences: Golem-III's dialogue of §9 (lines 1-41) with Luis.

The SitLog program ``butler.yaml`` runs over the skills in ``butler_home``; the KB
of Listing 3 lives in a SQLite store (a temporary file unless ``--kb-store`` names
one; naming it again runs another day with what the robot learnt) and every change
the dialogue makes to it is persisted there. Luis is simulated: he answers as in
the paper, or prefers coke and refuses to change the KB (``--prefers coke
--refuse-update``), or a person answers for him (``--interactive``); ``--tidy`` puts
the noodles and the coke where they belong, so nothing is misplaced; ``--level``
switches the simulator's disturbances on.
"""

from __future__ import annotations

import argparse
import re
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rich.console import Console

from homebot.events import Event
from homebot.knowledge import AddStatement, Kind, KnowledgeBase, parse_statement
from homebot.knowledge.store import KnowledgeStore
from homebot.scenarios.running import OptionKind, RunBuilder, ScenarioRun, SharedOption
from homebot.scenarios.summary import scenario_summary
from homebot.sim import InteractiveResponder, Responder, Simulation
from homebot.sim.people import normalise_question
from homebot.sitlog import Interpreter, load_program
from homebot.sitlog.functions.butler import ButlerHome
from homebot.sitlog.robot import SkillBody, SkillPerception
from homebot.world import PersonModel, World

__all__ = ["SHARED_OPTIONS", "LuisScript", "add_arguments", "butler_world", "run", "run_butler"]

SHARED_OPTIONS = (
    SharedOption(OptionKind.FIDELITY),
    SharedOption(OptionKind.DISTURBANCE_LEVEL, "--level", 0.0,
                 "disturbance level (0: none, as in the paper; 1: the demo's)"))

_WORK_DAY = 9 * 3600.0  #: how long Luis is away at work (simulated seconds)
_AT_THE_DOOR = (11.4, 2.8)
_ON_THE_COUCH = (1.3, 2.6)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--prefers", choices=("malz", "coke"), default="malz",
                        help="the drink Luis likes best (default malz, as in the paper)")
    parser.add_argument("--refuse-update", action="store_true",
                        help="Luis says no when asked to change an object's preferred location")
    parser.add_argument("--tidy", action="store_true",
                        help="the noodles and the coke are on their own shelves")
    parser.add_argument("--kb-store", metavar="FILE", default=None,
                        help="SQLite file that keeps the KB and its updates; run again with "
                        "the same file for another day with what the robot learnt")
    parser.add_argument("--interactive", action="store_true",
                        help="you answer for Luis at a prompt (his day goes on as scripted)")


@dataclass
class LuisScript:
    """Luis's answers and his day: off to work after the preferences, then to the couch."""

    prefers: str = "malz"
    refuse_update: bool = False
    typed: Responder | None = None  #: a person typing Luis's answers instead of the script
    simulation: Simulation | None = None
    at_work: bool = False  #: he has gone to work (and come back)
    ordered: bool = False  #: he has asked for something; he sits down once the robot goes
    heard: list[str] = field(default_factory=list)

    def __call__(self, person: PersonModel, question: str) -> str | None:
        if person.name != "Luis":
            return None
        answer = self._answer(normalise_question(question))
        if self.typed is not None:
            answer = self.typed(person, question)
            self.ordered = self.ordered or "do something for you" in normalise_question(question)
        if answer is not None:
            self.heard.append(answer)
        return answer

    def _answer(self, question: str) -> str | None:
        if "what do you like best" in question and self.prefers in question.split():
            return f"Hi, Golem. I like {self.prefers}."
        if "what do you like best" in question:
            return "I like noodles best."
        if "any more preferences" in question:
            return "No thanks, Golem; that is ok."
        if "how was your day" in question:
            return "I had a bad day!"
        if "do something for you" in question:
            self.ordered = True
            return "Bring me something to drink and biscuits."
        if "your favorite drink" in question:
            return "Yes."
        if "shall i bring you" in question:
            return "No, Golem, noodles are ok."
        if "change the preferred location" in question:
            return "No, Golem, leave it as it is." if self.refuse_update else "Yes, Golem, please."
        if "take it to its right shelf" in question:
            return "Yes, Golem, please."
        return None

    def notice(self, event: Event) -> None:
        """Luis's day: to work and back while the robot first drives off; to the couch,
        tired, once the robot sets off with his order."""
        if event.kind != "robot.path":
            return
        if not self.at_work:
            self.at_work = True
            self._walk(_AT_THE_DOOR, after=_WORK_DAY)
        elif self.ordered:
            self.ordered = False
            self._walk(_ON_THE_COUCH)

    def _walk(self, position: tuple[float, float], after: float = 0.0) -> None:
        if self.simulation is None:
            return
        if after:
            self.simulation.clock.advance(after)
        self.simulation.move_person("Luis", position)
        self.simulation.events.record("sim.story", person="Luis", position=list(position))


def butler_world(tidy: bool = False) -> World:
    """``butler_home``; tidied, the noodles and the coke are on their own shelves."""
    world = World.load("butler_home")
    if not tidy:
        return world
    data = world.to_dict()
    home = {"noodles": "shelf_food", "coke": "shelf_drinks"}
    for item in data["objects"]:
        item["placement"] = home.get(item["name"], item["placement"])
    return World.from_dict(data, source="butler_home (tidy)")


def run_butler(build: RunBuilder, *, prefers: str = "malz", refuse_update: bool = False,
               tidy: bool = False, kb_store: Path | None = None, seed: int = 0,
               typed: Responder | None = None, level: float = 0.0) -> dict[str, Any]:
    """Run the dialogue once; returns the summary (``transcript``, ``speech``, KB figures)."""
    world = butler_world(tidy)
    luis = LuisScript(prefers=prefers, refuse_update=refuse_update, typed=typed)
    run = build(world, seed=seed, responder=luis, level=level if level else None)
    luis.simulation = run.simulation
    run.simulation.events.listeners.append(luis.notice)
    with tempfile.TemporaryDirectory() as scratch:
        path = kb_store if kb_store is not None else Path(scratch) / "butler.db"
        if path.exists():  # another day with what the robot learnt before
            store = KnowledgeStore.open(path)
        else:
            store = KnowledgeStore.create(path, KnowledgeBase.load("butler").taxonomy,
                                          when=0.0, why="the KB of Listing 3")
        first_update = len(store.history())
        try:
            home = ButlerHome(store, run.context)
            if home.kb.value("malz", "healthier_than=>coke") != "yes":
                home.update(AddStatement(owner="malz", kind=Kind.RELATION,
                                         statement=parse_statement("healthier_than=>coke")),
                            "a general health recommendation")
            interpreter = Interpreter(load_program("butler"),
                                      SkillPerception(run.executive, person="Luis"),
                                      body=SkillBody(run.executive), application=home,
                                      executive=run.executive,
                                      on_transition=lambda step: run.context.events.record(
                                          "sitlog.transition", transition=str(step)))
            result = interpreter.run()
            log = store.history()
            why_user = [str(explanation) for explanation in home.kb.explanations(home.user_id)]
        finally:
            store.close()
        reopened = KnowledgeStore.open(path)
        persisted = reopened.kb.to_text() == home.kb.to_text()
        reopened.close()
    truth = run.simulation.object_location
    ordered = result.detail.globals.get("order", ())
    order = [str(item) for item in ordered] if isinstance(ordered, tuple) else []
    delivered = all(truth.get(item) == "person:Luis" for item in order)
    transcript = _transcript(run)
    return scenario_summary(
        "butler", delivered and bool(order) and persisted,
        [{"model": t.model, "situation": str(t.situation), "expectation": str(t.expectation),
          "action": str(t.action)} for t in result.detail.transitions()],
        [line["text"] for line in transcript if line["who"] == "robot"],
        transcript=transcript, order=order,
        objects={name: truth[name] for name in ("malz", "coke", "noodles", "bisquits")},
        kb_updates=[{"what": entry.what, "why": entry.why, "at": round(entry.when, 1)}
                    for entry in log[first_update:]],
        kb_persisted=persisted, kb_store=str(kb_store) if kb_store else None,
        why_user=why_user,
        situations=result.detail.situations, sim_time=round(run.robot.now(), 1))


def _transcript(run: ScenarioRun) -> list[dict[str, str]]:
    lines = []
    for event in run.simulation.events.events:
        if event.kind == "speech":
            lines.append({"who": "robot", "text": str(event.data["text"])})
        elif event.kind == "heard":
            lines.append({"who": str(event.data["person"]), "text": str(event.data["text"])})
    return lines


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """The dialogue of §9 with the variant the arguments choose."""
    summary = run_butler(build, prefers=args.prefers, refuse_update=args.refuse_update,
                         tidy=args.tidy, kb_store=Path(args.kb_store) if args.kb_store else None,
                         seed=args.seed, level=args.level,
                         typed=InteractiveResponder() if args.interactive else None)
    if console is not None:
        for number, line in enumerate(summary["transcript"], start=1):
            who = "Golem" if line["who"] == "robot" else line["who"]
            console.print(f"{number:>3}. [bold]{who}:[/] {line['text']}", highlight=False)
        console.print(f"\n{len(summary['kb_updates'])} KB updates persisted"
                      f"{' in ' + summary['kb_store'] if summary['kb_store'] else ''}; "
                      f"{summary['situations']} situations; "
                      f"{summary['sim_time']:.0f} s simulated", highlight=False)
        for update in summary["kb_updates"]:
            console.print(f"  - {update['why']}: {_describe(update['what'])}", highlight=False,
                          markup=False)
        console.print("Why Luis was looked for where he was (abduction over the KB): "
                      + "; ".join(summary["why_user"]), highlight=False, markup=False)
    return summary


def _describe(what: dict[str, Any]) -> str:
    statement = what.get("statement", "")
    return re.sub(r"\s+", " ", f"{what.get('type')} {what.get('owner', '')} {statement}").strip()
