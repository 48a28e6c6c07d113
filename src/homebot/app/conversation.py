"""A run's conversation: one person talking to the robot, as ``homebot chat``, ``homebot do
--answer`` and the web console's command box all hold it."""

from __future__ import annotations

from collections.abc import Callable

from homebot.app.run import Run
from homebot.executive.conversation import Conversation, Runner
from homebot.language import ReadingModel, Vocabulary
from homebot.world import World

__all__ = ["QUESTION_COST", "believed", "conversation_for", "told"]

#: what asking back costs, where doing the right thing is worth 1 and a wrong one costs 1
QUESTION_COST = 0.25


def conversation_for(run: Run, *, question_cost: float = QUESTION_COST,
                     listen: Callable[[], str | None] | None = None,
                     runner: Runner | None = None) -> Conversation:
    """A conversation in ``run``'s home that reads commands by the robot's beliefs.

    Args:
        question_cost: see ``QUESTION_COST``; an ambiguous command is carried out on its
            likeliest reading when that is worth more than asking.
        listen: what the person said while a task runs (asked between its steps).
        runner: runs each task (default: ``run.run``); the console passes its own, which
            keeps a failed task to help on with.
    """
    return Conversation(Vocabulary.from_world(run.world), runner or run.run, listen=listen,
                        readings=believed(run, question_cost))


def told(world: World, question_cost: float = QUESTION_COST) -> ReadingModel:
    """What the robot is told before it starts (the world file: where things are kept),
    as a reading model for a single command."""
    return ReadingModel(object_at={name: obj.placement for name, obj in world.objects.items()},
                        categories={name: obj.category for name, obj in world.objects.items()},
                        question=question_cost, places=len(world.placements))


def believed(run: Run, question_cost: float = QUESTION_COST) -> Callable[[], ReadingModel]:
    """The robot's current beliefs (never the simulator's truth) as a reading model."""
    def model() -> ReadingModel:
        beliefs = run.context.beliefs
        return ReadingModel(
            object_at={name: where for name, where in beliefs.object_at.items() if where},
            categories={name: obj.category for name, obj in run.world.objects.items()},
            question=question_cost, places=len(run.world.placements))
    return model
