"""HTN planning speed: our planner beside GTPyhop on the bring-object domain, and tidy-up scaling.

GTPyhop (``gtpyhop-core``, a dev dependency) gets the same decomposition as
``data/domains/home.jshop`` (announce, fetch from where the object was seen /
told / belongs, deliver, report), written the way GTPyhop domains are: state
variables in dicts, actions and methods as Python functions, over the same
beliefs. Both find their first plan; each is timed in the same run. Then the
paper's Table 1 figures, tidy-ups of growing numbers of misplaced objects, and
seeded bring tasks under disturbances carried out by the executive (GPSR steps)
and by the HTN actor (plan, monitor, replan), judged by ground truth.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import statistics
import time
from collections.abc import Callable
from functools import partial
from typing import Any

from rich.console import Console

from homebot.app import RunSettings, build_run, disturbed
from homebot.beliefs import Beliefs
from homebot.bench.arguments import add_plot_option, count, disturbance_level, seed
from homebot.htn import (
    Goal,
    Names,
    PlanActor,
    Planner,
    State,
    home_domain,
    state_from_beliefs,
)
from homebot.navigation import Navigator
from homebot.progress import track
from homebot.trials.fetch import delivered, fetch_tasks
from homebot.world import World

__all__ = ["add_arguments", "run"]

#### GTPyhop's version of the bring-object domain


def _gtpyhop() -> Any:
    # GTPyhop prints a banner when imported; keep the benchmark's output clean.
    with contextlib.redirect_stdout(io.StringIO()):
        import gtpyhop
    return gtpyhop


def _gtpyhop_available() -> bool:
    """Whether ``gtpyhop-core`` is installed (it is a dev dependency)."""
    try:
        _gtpyhop()
    except ImportError:
        return False
    return True


def _gtpyhop_state(gtpyhop: Any, state: State) -> Any:
    """Our planning state as GTPyhop state variables."""
    holds: dict[str, set[str]] = {}
    for _, placement, category in state.atoms("holds"):
        holds.setdefault(placement, set()).add(category)
    return gtpyhop.State(
        "home",
        at={atom[1]: atom[2] for atom in state.atoms("at")},
        free_hands={"robot": [atom[2] for atom in state.atoms("free-hand")]},
        holding={},
        object_at={atom[1]: atom[2] for atom in state.atoms("object-at")},
        told_at={atom[1]: atom[2] for atom in state.atoms("told-at")},
        category={atom[1]: atom[2] for atom in state.atoms("category")},
        holds=holds,
        placements={atom[1] for atom in state.atoms("placement")},
        rooms={atom[1] for atom in state.atoms("room")},
        room_of={atom[1]: atom[2] for atom in state.atoms("room-of")},
        person_in={atom[1]: atom[2] for atom in state.atoms("person-in")},
        ruled_out={(atom[1], atom[2]) for atom in state.atoms("ruled-out")},
        closed={atom[1] for atom in state.atoms("door-closed")},
        only_door={atom[2]: atom[1] for atom in state.atoms("only-door")},
        has=set(), told=set(), reported=set(), found=set(),
    )


def _declare_going(gtpyhop: Any) -> None:
    """The actions and ``go_to`` methods both GTPyhop domains share, as ``home.jshop`` has them."""

    def move_base(s: Any, r: str, source: str, target: str) -> Any:
        if s.at[r] == source:
            s.at[r] = target
            return s
        return None

    def open_door(s: Any, r: str, door: str) -> Any:
        if door in s.closed:
            s.closed.discard(door)
            return s
        return None

    def find_object(s: Any, r: str, o: str, p: str) -> Any:
        if s.at[r] == p:
            s.found.add((o, p))
            return s
        return None

    gtpyhop.declare_actions(move_base, open_door, find_object)

    def m_go_there(s: Any, r: str, place: str) -> Any:
        return [] if s.at[r] == place else False

    def m_go_in_room(s: Any, r: str, place: str) -> Any:
        return [] if place in s.rooms and s.room_of.get(s.at[r]) == place else False

    def m_go_door(s: Any, r: str, place: str) -> Any:
        room = s.room_of.get(place)
        door = s.only_door.get(room)
        if door in s.closed and s.room_of.get(s.at[r]) != room:
            return [("open_door", r, door), ("move_base", r, s.at[r], place)]
        return False

    def m_go_drive(s: Any, r: str, place: str) -> Any:
        return [("move_base", r, s.at[r], place)]

    gtpyhop.declare_task_methods("go_to", m_go_there, m_go_in_room, m_go_door, m_go_drive)


def _declare(gtpyhop: Any) -> None:
    """Declare the actions and methods in GTPyhop's current domain."""
    _declare_going(gtpyhop)

    def announce(s: Any, r: str, what: str, thing: str, who: str) -> Any:
        s.told.add((who, what, thing))
        return s

    def report(s: Any, r: str, what: str, thing: str, who: str) -> Any:
        s.reported.add((who, what, thing))  # GTPyhop leaves out actions that change nothing
        return s

    def grasp(s: Any, r: str, o: str, p: str) -> Any:
        if s.at[r] == p and (o, p) in s.found and s.free_hands[r]:
            hand = s.free_hands[r].pop(0)
            s.holding[o] = hand
            s.object_at.pop(o, None)
            s.found.discard((o, p))
            return s
        return None

    def find_person(s: Any, r: str, who: str) -> Any:
        if s.room_of.get(s.at[r]) == s.person_in.get(who):
            s.at[r] = who
            return s
        return None

    def hand_over(s: Any, r: str, o: str, who: str) -> Any:
        if s.at[r] == who and o in s.holding:
            s.free_hands[r].append(s.holding.pop(o))
            s.has.add((who, o))
            return s
        return None

    gtpyhop.declare_actions(announce, report, grasp, find_person, hand_over)

    def excluded(s: Any, o: str, p: str) -> bool:
        return (o in s.object_at and s.object_at[o] != p) or (o, p) in s.ruled_out or (
            o in s.holding)

    def m_bring_delivered(s: Any, r: str, o: str, who: str) -> Any:
        return [] if (who, o) in s.has else False

    def m_bring_held(s: Any, r: str, o: str, who: str) -> Any:
        if o in s.holding:
            return [("announce_task", r, "bring", o, who), ("deliver", r, o, who),
                    ("report", r, "bring", o, who)]
        return False

    def m_bring_fetch(s: Any, r: str, o: str, who: str) -> Any:
        return [("announce_task", r, "bring", o, who), ("fetch", r, o),
                ("deliver", r, o, who), ("report", r, "bring", o, who)]

    def m_fetch_seen(s: Any, r: str, o: str) -> Any:
        p = s.object_at.get(o)
        if p in s.placements:
            return [("go_to", r, p), ("find_object", r, o, p), ("grasp", r, o, p)]
        return False

    def m_fetch_told(s: Any, r: str, o: str) -> Any:
        p = s.told_at.get(o)
        if p is not None and not excluded(s, o, p):
            return [("go_to", r, p), ("find_object", r, o, p), ("grasp", r, o, p)]
        return False

    def m_fetch_belongs(s: Any, r: str, o: str) -> Any:
        category = s.category.get(o)
        for p, categories in s.holds.items():
            if category in categories and not excluded(s, o, p):
                return [("go_to", r, p), ("find_object", r, o, p), ("grasp", r, o, p)]
        return False

    def m_deliver_with(s: Any, r: str, o: str, who: str) -> Any:
        return [("hand_over", r, o, who)] if s.at[r] == who else False

    def m_deliver_go(s: Any, r: str, o: str, who: str) -> Any:
        room = s.person_in.get(who)
        if room is None:
            return False
        return [("go_to", r, room), ("find_person", r, who), ("hand_over", r, o, who)]

    def m_announce_told(s: Any, r: str, what: str, thing: str, who: str) -> Any:
        return [] if (who, what, thing) in s.told else False

    def m_announce(s: Any, r: str, what: str, thing: str, who: str) -> Any:
        return [("announce", r, what, thing, who)]

    gtpyhop.declare_task_methods("bring_object", m_bring_delivered, m_bring_held, m_bring_fetch)
    gtpyhop.declare_task_methods("fetch", m_fetch_seen, m_fetch_told, m_fetch_belongs)
    gtpyhop.declare_task_methods("deliver", m_deliver_with, m_deliver_go)
    gtpyhop.declare_task_methods("announce_task", m_announce_told, m_announce)


def _gtpyhop_bring_object(state: State) -> tuple[Any, Any, Any]:
    """GTPyhop's module, its state for ``state`` and a fresh bring-object domain (made current)."""
    gtpyhop = _gtpyhop()
    with contextlib.redirect_stdout(io.StringIO()):
        gtpyhop.Domain("homebot_bring_object")
        gtpyhop.set_verbose_level(0)
        gtpyhop.set_recursive_planning(True)
        _declare(gtpyhop)
    return gtpyhop, _gtpyhop_state(gtpyhop, state), gtpyhop.current_domain


#### GTPyhop's version of the tidy-up


def _declare_tidy(gtpyhop: Any) -> None:
    """The tidy-up of ``home.jshop`` (tidy, tidy_from, put_away, go_to) in GTPyhop's style."""
    _declare_going(gtpyhop)

    def grasp(s: Any, r: str, o: str, p: str) -> Any:
        if s.at[r] == p and (o, p) in s.found and s.free_hands[r]:
            s.holding[o] = s.free_hands[r].pop(0)
            s.object_at.pop(o, None)
            s.found.discard((o, p))
            return s
        return None

    def put_down(s: Any, r: str, o: str, p: str) -> Any:
        if s.at[r] == p and o in s.holding:
            s.free_hands[r].append(s.holding.pop(o))
            s.object_at[o] = p
            return s
        return None

    gtpyhop.declare_actions(grasp, put_down)

    def belongs(s: Any, o: str) -> list[str]:
        category = s.category.get(o)
        return [p for p, c in s.holds_in_order if c == category]

    def misplaced(s: Any, only: str | None = None) -> tuple[str, str, str] | None:
        for o, place in s.object_at.items():
            if (only is None or o == only) and place in s.placements:
                targets = belongs(s, o)
                if place not in targets and targets:
                    return o, place, targets[0]
        return None

    def m_tidy_next(s: Any, r: str) -> Any:
        found = misplaced(s)
        return [("tidy_from", r, *found), ("tidy", r)] if found else False

    def m_tidy_done(s: Any, r: str) -> Any:
        return []

    def m_two_on_the_tray(s: Any, r: str, o1: str, source: str, target: str) -> Any:
        if len(set(s.free_hands[r])) < 2:
            return False
        for o2, place in s.object_at.items():
            if o2 != o1 and place == source and place in s.placements:
                targets = belongs(s, o2)
                if place not in targets and targets and targets[0] == target:
                    return [("go_to", r, source), ("find_object", r, o1, source),
                            ("grasp", r, o1, source), ("find_object", r, o2, source),
                            ("grasp", r, o2, source), ("go_to", r, target),
                            ("put_down", r, o1, target), ("put_down", r, o2, target)]
        return False

    def m_one(s: Any, r: str, o1: str, source: str, target: str) -> Any:
        return [("put_away", r, o1)]

    def m_put_away(s: Any, r: str, o: str) -> Any:
        found = misplaced(s, o)
        if found is None:
            return []
        _, source, target = found
        return [("go_to", r, source), ("find_object", r, o, source), ("grasp", r, o, source),
                ("go_to", r, target), ("put_down", r, o, target)]

    gtpyhop.declare_task_methods("tidy", m_tidy_next, m_tidy_done)
    gtpyhop.declare_task_methods("tidy_from", m_two_on_the_tray, m_one)
    gtpyhop.declare_task_methods("put_away", m_put_away)


def _gtpyhop_tidy(gtpyhop: Any, state: State, robot: str) -> tuple[Any, float, Any]:
    """GTPyhop's first plan for the tidy-up of ``state``: (plan, milliseconds, domain)."""
    with contextlib.redirect_stdout(io.StringIO()):
        gtpyhop.Domain("homebot_tidy")
        gtpyhop.set_verbose_level(0)
        gtpyhop.set_recursive_planning(False)  # hundreds of objects: no Python recursion
        _declare_tidy(gtpyhop)
        gt_state = _gtpyhop_state(gtpyhop, state)
        gt_state.holds_in_order = [(atom[1], atom[2]) for atom in state.atoms("holds")]
        began = time.perf_counter()
        plan = gtpyhop.find_plan(gt_state, [("tidy", robot)])
        elapsed = (time.perf_counter() - began) * 1000
    return plan, elapsed, gtpyhop.current_domain


#### timing


def _median_ms(action: Callable[[], Any], repeats: int) -> tuple[float, Any]:
    """The median wall time of ``action`` in milliseconds, and its last result."""
    samples = []
    result = None
    for _ in range(repeats):
        began = time.perf_counter()
        result = action()
        samples.append(time.perf_counter() - began)
    return 1000 * statistics.median(samples), result


def _tidy_world(base: World, misplaced: int) -> World:
    """``base``'s map with ``misplaced`` objects, each on a placement not meant for it."""
    data = base.to_dict()
    categories = [c.name for c in base.categories.values() if base.placements_holding(c.name)]
    placements = list(base.placements.values())
    objects = []
    for index in range(misplaced):
        category = categories[index % len(categories)]
        wrong = [p.name for p in placements if category not in p.holds]
        objects.append({"name": f"item {index + 1:03d}", "category": category,
                        "placement": wrong[(index * 7) % len(wrong)]})
    data["objects"] = objects
    return World.from_dict(data, f"<{base.name} with {misplaced} misplaced objects>")


def _execution(world: World, runs: int, seed: int, level: float) -> list[dict[str, Any]]:
    """The same seeded bring tasks under disturbances: GPSR steps with the executive's
    recovery protocols, and HTN goals with per-operator monitoring and replanning."""
    navigator = Navigator(world)
    domain = home_domain()
    rows = []
    for mode in ("executive (GPSR steps + recovery)", "htn (plan + monitor + replan)"):
        delivered_count = verified = told = 0
        sim_times: list[float] = []
        for index, fetch in enumerate(track(fetch_tasks(world, runs, seed),
                                            f"bring tasks, {mode.split()[0]}")):
            simulation_run = build_run(RunSettings(
                world=world, seed=seed * 100_003 + index, disturbances=disturbed(level),
                navigator=navigator))
            if mode.startswith("htn"):
                names = Names()
                goal = Goal.of("bring_object", [fetch.obj, fetch.person], world, names, domain)
                done = PlanActor(simulation_run.executive, domain).run(goal, names)
                success, speech, sim_time = done.success, done.speech, done.sim_time
            else:
                report = simulation_run.run(fetch.task)
                success, speech, sim_time = report.success, report.speech, report.sim_time
            really = delivered(simulation_run.simulation, fetch)
            delivered_count += really
            verified += really and success
            told += not success and any(text.startswith("I am sorry") for text in speech)
            sim_times.append(sim_time)
        rows.append({"mode": mode, "tasks": runs, "delivered": delivered_count,
                     "verified_delivery_rate": round(verified / max(runs, 1), 4),
                     "failed_and_told_why": told,
                     "median_sim_time_s": round(statistics.median(sim_times or [0.0]), 1)})
    return rows


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--repeats", type=count("--repeats", 1, 100_000), default=300,
                        help="plans timed per planner")
    parser.add_argument("--sizes", type=count("--sizes", 1, 5_000), nargs="+",
                        default=[25, 50, 100, 200],
                        help="numbers of misplaced objects to tidy up")
    parser.add_argument("--runs", type=count("--runs", 0, 20_000), default=60,
                        help="seeded bring tasks run under disturbances per mode (0: none)")
    parser.add_argument("--level", type=disturbance_level, default=1.0, help="disturbance level")
    parser.add_argument("--seed", type=seed, default=1, help="seed of tasks and disturbances")
    add_plot_option(parser, "tidy-up planning time by the number of misplaced objects")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Table 1 figures, our median beside GTPyhop's on bring-object, and tidy-up scaling."""
    world = World.load("apartment")
    domain = home_domain()
    state, names = state_from_beliefs(world, Beliefs.from_world(world), world.robot.pose.xy())
    planner = Planner(domain)
    bring = Goal.of("bring_object", ["pringles", "Alex"], world, names, domain)
    guide = Goal.of("guide_person", ["Alex", "bedroom"], world, names, domain)
    figures: dict[str, Any] = {}
    table: dict[str, Any] = {}
    for label, goal in (("bring object", bring), ("guide robot", guide)):
        every_ms, every = _median_ms(partial(planner.search, state, [goal.task], limit=None),
                                     max(1, args.repeats // 10))
        table[label] = {"plans": len(every.plans),
                        "shortest": min(len(p) for p in every.plans),
                        "identical_sequences": len({tuple(p.actions()) for p in every.plans}) == 1,
                        "all_plans_ms": round(every_ms, 4)}
    figures["table1"] = table
    ours_ms, ours = _median_ms(partial(planner.search, state, [bring.task]), args.repeats)
    comparison: dict[str, Any] = {"homebot_median_ms": round(ours_ms, 4)}
    try:
        gtpyhop, gt_state, _ = _gtpyhop_bring_object(state)
    except ImportError:
        comparison["gtpyhop"] = "not installed (pip install gtpyhop-core, the dev extra)"
    else:
        task = [("bring_object", *bring.task[1:])]
        with contextlib.redirect_stdout(io.StringIO()):
            gt_ms, gt_plan = _median_ms(partial(gtpyhop.find_plan, gt_state, task), args.repeats)
        comparison.update(
            gtpyhop_median_ms=round(gt_ms, 4),
            gtpyhop_over_homebot_in_this_run=round(gt_ms / ours_ms, 2),
            same_plan=[tuple(a) for a in gt_plan] == [
                (s.operator[1:], *s.args) for s in ours.plan.steps])
    figures["bring_object_first_plan"] = comparison
    tidy: list[dict[str, Any]] = []
    for size in track(args.sizes, "tidy-up plans, by size"):
        messy = _tidy_world(world, size)
        messy_state, messy_names = state_from_beliefs(messy, Beliefs.from_world(messy),
                                                      messy.robot.pose.xy())
        goal = Goal.of("tidy", [], messy, messy_names, domain)
        tidy_ms, result = _median_ms(partial(planner.search, messy_state, [goal.task]), 3)
        moved = sum(1 for step in result.plan.steps if step.operator == "!put_down")
        repeated = planner.search(messy_state, [goal.task]).plan
        row: dict[str, Any] = {
            "misplaced": size, "put_away": moved, "plan_length": len(result.plan),
            "ms": round(tidy_ms, 2), "ms_per_object": round(tidy_ms / size, 3),
            "same_plan_when_repeated": repeated is not None and (
                repeated.actions() == result.plan.actions())}
        if _gtpyhop_available():
            samples, gt_plan = [], None
            for _ in range(3):
                gt_plan, gt_ms, _ = _gtpyhop_tidy(_gtpyhop(), messy_state, goal.task[1])
                samples.append(gt_ms)
            gt_median = statistics.median(samples)
            row.update(gtpyhop_ms=round(gt_median, 2),
                       gtpyhop_plan_length=len(gt_plan) if gt_plan else None,
                       gtpyhop_same_plan=bool(gt_plan) and [tuple(a) for a in gt_plan] == [
                           (s.operator[1:], *s.args) for s in result.plan.steps],
                       gtpyhop_over_homebot_in_this_run=round(gt_median / tidy_ms, 2))
        tidy.append(row)
    figures["tidy"] = tidy
    figures["execution"] = _execution(world, args.runs, args.seed, args.level) if args.runs else []
    if console is not None:
        for label, row in table.items():
            console.print(f"Table 1, {label}: {row['plans']} plans, shortest {row['shortest']}, "
                          f"identical action sequences: {row['identical_sequences']}, every "
                          f"plan in {row['all_plans_ms']} ms (JSHOP2: 3 s / 1.5 s, quoted from "
                          "the Care-O-bot paper, not measured)")
        console.print(f"bring_object, first plan: {comparison}")
        for row in tidy:
            console.print(f"tidy-up: {row}")
        for row in figures["execution"]:
            console.print(f"bring under disturbances x{args.level}: {row}")
    if args.plot is not None:
        from homebot.bench.plots import htn_figure, save

        save(htn_figure(tidy), args.plot)
    return {"benchmark": "htn", "figures": figures}
