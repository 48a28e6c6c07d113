"""One guiding episode, wired: the embodied robot in a ``homebot.trials.guiding`` arena runs
its Guide skill; the arena's referee judges by the truth."""

from __future__ import annotations

from typing import TYPE_CHECKING

from homebot.app.embodied import embodied_robot_in
from homebot.beliefs import Beliefs
from homebot.navigation import Navigator
from homebot.world import World

if TYPE_CHECKING:
    from homebot.trials.guiding import GuideArena, GuideEpisode

__all__ = ["guide_episode", "run_guide"]


def guide_episode(world: World, seed: int, navigator: Navigator) -> GuideEpisode:
    """One seeded guiding episode: the embodied robot, told where it starts and that it
    has found the person in front of it, guides them to the goal with the Guide skill
    (execute and monitor, by its own perception); the verdict is the referee's."""
    from homebot.trials.guiding import GuideEpisode, guide_arena

    arena = guide_arena(world, seed, navigator)
    if isinstance(arena, GuideEpisode):
        return arena
    return run_guide(arena, navigator)


def run_guide(arena: GuideArena, navigator: Navigator) -> GuideEpisode:
    """The embodied robot in ``arena`` (told where it starts and whom it found) runs its
    Guide skill to the arena's goal; the referee's verdict."""
    from homebot.sim.body import SimBody
    from homebot.skills import SkillContext
    from homebot.skills.motion import Guide

    world = arena.sim.world
    robot = embodied_robot_in(arena.sim, navigator)
    robot.localisation.initialise(arena.robot_pose, spread=0.05, angle_spread=0.05)
    body = robot.body
    assert isinstance(body, SimBody)
    beliefs = Beliefs.from_world(world, arena.sim.events)
    context = SkillContext(robot=robot, world=world, navigator=navigator, beliefs=beliefs,
                           events=arena.sim.events, bindings={"person": arena.person})
    arena.start(body)
    outcome = Guide().run(context, {"to": arena.goal, "person": arena.person})
    return arena.judge(outcome.status.value)
