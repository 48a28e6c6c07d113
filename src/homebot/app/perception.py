"""A run's perception, wired to the simulator: recognisers and face memories trained on
rendered views.

The recogniser of ``homebot.perception`` learns from labelled frames; here the
simulator renders them (``homebot.sim.tabletop``): generated table-top scenes of
the world's catalogue objects, segmented by the same pipeline the robot runs.
A trained recogniser is kept per catalogue for the life of the process, so the
runs of one benchmark train once, and on disk (``homebot.app.cache``) for the next
process, as is a household's face memory.
"""

from __future__ import annotations

import copy
import functools
import math
import os
import pickle
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import TypeVar

import numpy as np

import homebot.perception.faces as faces_module
import homebot.perception.recognition as recognition_module
import homebot.perception.tabletop as perception_tabletop_module
import homebot.robot.camera as robot_camera_module
import homebot.sim.camera as sim_camera_module
import homebot.sim.faces as sim_faces_module
import homebot.sim.tabletop as sim_tabletop_module
from homebot import progress
from homebot.app.cache import cache_directory, cache_key
from homebot.perception.faces import FaceDetector, FaceMemory, Window
from homebot.perception.recognition import (
    LabelledFrame,
    Recogniser,
    TabletopPerception,
    training_examples,
)
from homebot.sim.faces import background_patch, face_identity, face_view
from homebot.sim.tabletop import tabletop_scene
from homebot.world import CatalogueEntry, World, object_catalogue

__all__ = ["face_memory", "household_faces", "labelled_frames", "perception_for",
           "trained_face_detector", "trained_recogniser"]

_Model = TypeVar("_Model")

_ENROLMENT_VIEWS = 20  #: face views of each member of the household the robot was taught
_VIEWS_PER_OBJECT = 12  #: training views of each catalogue object (about)
_OBJECTS_PER_SCENE = (4, 9)  #: training scenes hold 4 to 8 objects


def labelled_frames(catalogue: Mapping[str, CatalogueEntry], scenes: int,
                    rng: np.random.Generator) -> Iterator[LabelledFrame]:
    """``scenes`` rendered table-top frames of catalogue objects, with their truth."""
    entries = list(catalogue.values())
    for _ in range(scenes):
        scene = tabletop_scene(entries, int(rng.integers(*_OBJECTS_PER_SCENE)), rng)
        yield scene.frame, [(placed.entry.name, placed.position) for placed in scene.objects]


def trained_recogniser(catalogue: Mapping[str, CatalogueEntry], seed: int = 0) -> Recogniser:
    """A recogniser for ``catalogue``, trained on views rendered with ``seed`` (remembered)."""
    return _trained(tuple(sorted(catalogue.items())), seed)


@functools.lru_cache(maxsize=8)
def _trained(items: tuple[tuple[str, CatalogueEntry], ...], seed: int) -> Recogniser:
    """The trained recogniser, from the disk cache when this code trained it before
    (rendering and segmenting its views takes seconds of CPU in every new process)."""
    key = cache_key((items, seed, _VIEWS_PER_OBJECT, _OBJECTS_PER_SCENE),
                    (recognition_module, perception_tabletop_module, sim_tabletop_module,
                     sim_camera_module, robot_camera_module))
    cached = cache_directory() / f"recogniser-{key}.pickle"
    loaded = _kept(cached, Recogniser)
    if loaded is not None:
        return loaded
    recogniser = _train(dict(items), seed)
    _keep(cached, recogniser)
    return recogniser


def _train(catalogue: dict[str, CatalogueEntry], seed: int) -> Recogniser:
    rng = np.random.default_rng([seed, 1515])
    mean_objects = sum(_OBJECTS_PER_SCENE) / 2 - 0.5
    scenes = math.ceil(_VIEWS_PER_OBJECT * len(catalogue) / mean_objects)
    frames = progress.track(labelled_frames(catalogue, scenes, rng),
                            "learning the objects from rendered table tops", total=scenes)
    features, labels = training_examples(frames, rng)
    recogniser = Recogniser(catalogue, seed=seed)
    with progress.task("learning the objects: growing the forest"):
        return recogniser.fit(features, labels) if labels else recogniser


def perception_for(world: World, seed: int = 0) -> TabletopPerception:
    """The table-top pipeline for ``world``'s catalogue (trained once per catalogue)."""
    recogniser = trained_recogniser(object_catalogue(world))
    return TabletopPerception(recogniser, np.random.default_rng([seed, 1516]))


@functools.lru_cache(maxsize=2)
def stranger_faces(seed: int = 0, strangers: int = 30, views: int = 300
                   ) -> tuple[tuple[np.ndarray, Window, str], ...]:
    """``views`` rendered views of ``strangers`` people (nobody of any home): each image,
    where its face is and whose it is. The face cascade learns from them what a face is,
    and the face memory whom a newcomer's face might be as near as to someone it knows
    (remembered: both ask for them)."""
    rng = np.random.default_rng([seed, 1517])
    people = [face_identity(f"stranger{i}", seed + 1) for i in range(strangers)]
    return tuple((*face_view(people[i % strangers], rng), people[i % strangers].name)
                 for i in progress.track(range(views), "rendering strangers' faces"))


@functools.lru_cache(maxsize=4)
def trained_face_detector(seed: int = 0, strangers: int = 30, views: int = 300,
                          faceless: int = 200) -> FaceDetector:
    """A face cascade trained on ``stranger_faces`` and ``faceless`` clutter images
    (remembered: training takes tens of seconds)."""
    rendered = stranger_faces(seed, strangers, views)
    rng = np.random.default_rng([seed, 1519])
    detector = FaceDetector(seed=seed)
    with progress.task("training the face detector"):
        detector.train([image for image, _, _ in rendered], [window for _, window, _ in rendered],
                       [background_patch(rng) for _ in range(faceless)])
    return detector


def face_memory(seed: int = 0) -> FaceMemory:
    """An empty face memory over the trained detector, for people to be enrolled in; it
    knows the detector's training faces as strangers' (``FaceMemory.enrol_strangers``)."""
    memory = FaceMemory(trained_face_detector(seed), seed=seed)
    rendered = stranger_faces(seed)
    with progress.task("learning strangers' faces"):
        memory.enrol_strangers([image for image, _, _ in rendered],
                               [name for _, _, name in rendered])
    return memory


def household_faces(world: World) -> FaceMemory:
    """A face memory that knows the people of ``world``'s file by face, as a robot
    taught its household before its first day: each person's ``_ENROLMENT_VIEWS`` views,
    rendered as the head camera would take them (``sim.faces``). Visitors who come
    later are strangers until they say their name. The robot's software is the same
    whatever the run's seed, so the taught memory is built once per household and
    process, and each robot gets its own copy to enrol newcomers in."""
    names = tuple(person.name for person in world.model.people)
    return copy.deepcopy(_taught(names))


@functools.lru_cache(maxsize=4)
def _taught(names: tuple[str, ...]) -> FaceMemory:
    """The taught memory, from the disk cache when this code made it before (training
    the detector and enrolling a household take tens of seconds of CPU)."""
    key = cache_key((names, _ENROLMENT_VIEWS),
                    (faces_module, sim_faces_module))
    cached = cache_directory() / f"household-{key}.pickle"
    loaded = _kept(cached, FaceMemory)
    if loaded is not None:
        return loaded
    with progress.task(f"teaching the robot its household's faces (the first run only: "
                       f"kept in {cache_directory()} after)"):
        memory = face_memory()
        rng = np.random.default_rng([0, 1518])
        views = {name: [face_view(face_identity(name, 0), rng)[0]
                        for _ in range(_ENROLMENT_VIEWS)] for name in names}
        with progress.task(f"enrolling {len(names)} people"):
            memory.enrol_people(views)
    _keep(cached, memory)
    return memory


def _kept(cached: Path, kind: type[_Model]) -> _Model | None:
    """The ``kind`` pickled at ``cached`` by an earlier process; None when there is none
    (or it is unreadable, or something else)."""
    try:
        loaded = pickle.loads(cached.read_bytes())
    except (OSError, pickle.UnpicklingError, EOFError, AttributeError):
        return None
    return loaded if isinstance(loaded, kind) else None


def _keep(cached: Path, model: object) -> None:
    """Pickle ``model`` to ``cached`` for the next process."""
    try:
        cached.parent.mkdir(parents=True, exist_ok=True)
        # written whole, then renamed: another process may be reading it meanwhile
        partial = cached.with_suffix(f".{os.getpid()}.partial")
        partial.write_bytes(pickle.dumps(model))
        os.replace(partial, cached)
    except OSError:
        pass  # a read-only home: train again next time

