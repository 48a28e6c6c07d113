"""The simulated components: seeded crashes, interrupted task actions, failing restarts."""

from __future__ import annotations

from homebot.navigation import Navigator
from homebot.sim.components import ComponentSimulation, SimulatedComponent

MODULE = ("off", "starting", "running", "failed")


def _simulation(seed: int = 0, **options: float) -> ComponentSimulation:
    components = [SimulatedComponent("laser", "module", MODULE, "off", {"start": 2.0}),
                  SimulatedComponent("arm", "posture", ("parked", "unparked"), "parked",
                                     {"set_posture": 3.0})]
    return ComponentSimulation(components, seed=seed, **options)


def test_a_start_passes_through_starting_and_takes_its_duration() -> None:
    simulation = _simulation()
    assert simulation.operate("start", "laser")
    assert simulation.now == 2.0 and simulation.state["laser"] == "running"
    states = [e["state"] for e in simulation.events if e["kind"] == "component"
              and e["component"] == "laser"]
    assert states == ["off", "starting", "running"]
    assert not simulation.operate("start", "laser")  # only from off
    assert simulation.operate("set_posture", "arm", "unparked")
    assert simulation.state["arm"] == "unparked" and simulation.now == 5.0
    assert not simulation.operate("restart", "arm")  # a posture does not restart


def test_a_crash_of_a_watched_module_stops_the_task_action_at_the_crash() -> None:
    simulation = _simulation(seed=3, mean_time_to_failure=10.0)
    simulation.operate("start", "laser")
    crash = simulation.crash_at["laser"]
    crashed = simulation.task("goto", 1000.0, {"laser": ("running", True)})
    assert crashed == "laser" and simulation.now == crash
    assert simulation.state["laser"] == "failed"
    end = simulation.events[-1]
    assert end["kind"] == "task.end" and end["interrupted"] == "laser"


def test_an_unwatched_crash_lets_the_action_run_its_time() -> None:
    simulation = _simulation(seed=3, mean_time_to_failure=10.0)
    simulation.operate("start", "laser")
    assert simulation.task("say", 1000.0) is None
    assert simulation.now == 1002.0 and simulation.state["laser"] == "failed"


def test_restarts_fail_as_often_as_configured_and_the_seed_decides() -> None:
    results = []
    for seed in range(200):
        simulation = _simulation(seed=seed, restart_failure=0.25)
        simulation.operate("start", "laser")
        results.append(simulation.operate("restart", "laser"))
    assert 30 <= results.count(False) <= 70
    again = []
    for seed in range(200):
        simulation = _simulation(seed=seed, restart_failure=0.25)
        simulation.operate("start", "laser")
        again.append(simulation.operate("restart", "laser"))
    assert again == results


def test_the_body_laser_sees_only_while_its_component_runs() -> None:
    from homebot.sim.body import SimBody
    from homebot.sim.simulation import Simulation
    from homebot.world import World

    components = _simulation(seed=1, mean_time_to_failure=2.0)
    components.components["laser"] = SimulatedComponent("laser", "module", MODULE, "off",
                                                        {"start": 0.05})
    apartment = World.load("apartment")
    body = SimBody(Simulation(apartment, seed=0, navigator=Navigator(apartment)),
                   components=components)
    assert not body.scan().valid().any()  # off: nothing returns
    components.operate("start", "laser")
    body.tick()
    assert components.state["laser"] == "running" and body.scan().valid().any()
    while components.state["laser"] == "running":  # crashes on the body's clock
        body.tick(5)
    assert components.now == body.now() and not body.scan().valid().any()
