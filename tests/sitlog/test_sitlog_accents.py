"""Dialogue models with accented names (issue 22): atoms in any script, speech and
membership compared folded, skills bound to the world's spelling."""

from __future__ import annotations

from pathlib import Path

from homebot.app import RunSettings, build_run
from homebot.sitlog import Interpreter, Var, format_term, load_program, parse_term
from homebot.sitlog.functions.behaviours import member
from homebot.sitlog.perception import utterance_term
from homebot.sitlog.robot import SkillBody, SkillPerception
from homebot.sitlog.terms import Struct, resolve
from homebot.world import World

CASA = Path(__file__).resolve().parents[1] / "world" / "data" / "casa.yaml"


def test_atoms_and_variables_in_any_script() -> None:
    variables: dict[str, Var] = {}
    term = parse_term("give(crème_brûlée, 'Patrícia', Søren, Øst)", "<test>", variables)
    assert isinstance(term, Struct)
    assert term.args[:2] == ("crème_brûlée", "Patrícia")
    assert set(variables) == {"Søren", "Øst"}
    assert format_term(term) == "give(crème_brûlée,'Patrícia',Søren,Øst)"


def test_heard_words_meet_an_expectation_without_its_accents() -> None:
    assert utterance_term("Jose, please.", ("josé", "søren")) == "josé"
    assert utterance_term("SOREN, thanks", ("josé", "søren")) == "søren"
    assert utterance_term("Crème brûlée", ()) == "crème brûlée"


def test_member_compares_atoms_folded() -> None:
    seen = ("crème brûlée", "crêpe")
    assert member(None, "creme brulee", seen, "yes", "no") == "yes"  # type: ignore[arg-type]
    assert member(None, "crepe", seen, "yes", "no") == "yes"  # type: ignore[arg-type]
    assert member(None, "crep", seen, "yes", "no") == "no"  # type: ignore[arg-type]


def test_find_in_the_accented_world_takes_names_without_accents() -> None:
    run = build_run(RunSettings(world=World.load(CASA), seed=1))
    variables: dict[str, Var] = {}
    term = parse_term("find('creme brulee', [etagere, 'MESA DA COZINHA'], Where)", "<test>",
                      variables)
    result = Interpreter(load_program("behaviours"), SkillPerception(run.executive),
                         body=SkillBody(run.executive), application=run.context).run(term)
    assert format_term(result.detail.final) == "ok"
    assert resolve(variables["Where"]) == "MESA DA COZINHA"
    looked = [event.data for event in run.simulation.events.of_kind("skill.start")
              if event.data.get("skill") == "look"]
    assert [entry["args"]["placement"] for entry in looked] == ["étagère", "mesa da cozinha"]
