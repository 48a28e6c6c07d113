"""Issue 12: everyday commands over two worlds, and commands that must never be a false ok.

``everyday.yaml`` (>= 300 commands as people say them, with the steps they mean) must parse
to those steps in >= 95 % of cases; ``no_false_success.yaml`` (>= 100 commands with a
part the robot cannot do or cannot place) must never parse as ok.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path
from typing import Any

import yaml
from step_notation import parse_steps

from homebot.language import ParseStatus, Vocabulary, parse_command
from homebot.world import World

_HERE = Path(__file__).parent
EVERYDAY: dict[str, list[dict[str, Any]]] = yaml.safe_load(
    (_HERE / "everyday.yaml").read_text(encoding="utf-8"))
NO_FALSE_SUCCESS: dict[str, list[str]] = yaml.safe_load(
    (_HERE / "no_false_success.yaml").read_text(encoding="utf-8"))


@cache
def _vocabulary(world: str) -> Vocabulary:
    return Vocabulary.from_world(World.load(world))


def everyday_mismatches(sets: dict[str, list[dict[str, Any]]] | None = None,
                        ) -> tuple[int, list[tuple[str, str, Any, Any]]]:
    """How many everyday cases there are, and the ones that parse to other steps."""
    wrong, total = [], 0
    for world, cases in (EVERYDAY if sets is None else sets).items():
        for case in cases:
            total += 1
            result = parse_command(case["say"], _vocabulary(world))
            got = result.to_dict()["steps"] if result else result.to_dict()
            expected = parse_steps(case["steps"])
            if got != expected:
                wrong.append((world, case["say"], expected, got))
    return total, wrong


def false_successes() -> tuple[int, list[tuple[str, str, Any]]]:
    """How many must-not-be-ok commands there are, and the ones that parse as ok."""
    wrong, total = [], 0
    for world, texts in NO_FALSE_SUCCESS.items():
        for text in texts:
            total += 1
            result = parse_command(text, _vocabulary(world))
            if result.status is ParseStatus.OK:
                wrong.append((world, text, result.to_dict()["steps"]))
    return total, wrong


def test_the_sets_are_large_varied_and_over_two_worlds() -> None:
    texts = [case["say"] for cases in EVERYDAY.values() for case in cases]
    assert len(texts) >= 300 and len(EVERYDAY) >= 2
    assert all(len(set(case["say"] for case in cases)) == len(cases)
               for cases in EVERYDAY.values())
    assert sum(len(texts) for texts in NO_FALSE_SUCCESS.values()) >= 100


def test_everyday_commands_parse_to_their_steps() -> None:
    total, wrong = everyday_mismatches()
    rate = 1 - len(wrong) / total
    detail = "\n".join(f"[{w}] {text}\n  expected {e}\n  got      {g}" for w, text, e, g in wrong)
    assert rate >= 0.95, f"{rate:.1%} right; wrong:\n{detail}"


def test_no_command_with_a_part_not_understood_is_ok() -> None:
    _total, wrong = false_successes()
    assert not wrong, "\n".join(f"[{w}] {text}: {steps}" for w, text, steps in wrong)


if __name__ == "__main__":  # first-sight / progress figures
    count, bad = everyday_mismatches()
    print(f"everyday: {count - len(bad)}/{count} exact ({100 * (1 - len(bad) / count):.1f} %)")
    held_out = yaml.safe_load((_HERE / "everyday_heldout.yaml").read_text(encoding="utf-8"))
    count, bad = everyday_mismatches(held_out)
    print(f"held out (written after tuning, never tuned on): {count - len(bad)}/{count}")
    count, bad_ok = false_successes()
    print(f"no false success: {len(bad_ok)} false ok of {count}")
