"""Faces: integral image, Haar features, the trained cascade, enrolment and identification."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("sklearn")

from homebot.errors import FaceError
from homebot.perception.faces import (
    FaceDetector,
    FaceMemory,
    HaarFeatures,
    _overlap,
    integral_image,
    moment_integrals,
)
from homebot.sim.faces import face_identity, face_view


def test_the_integral_image_sums_any_rectangle_in_four_look_ups() -> None:
    image = np.arange(20, dtype=float).reshape(4, 5)
    integral, _ = integral_image(image)
    r0, r1, c0, c1 = 1, 3, 2, 5
    total = integral[r1, c1] - integral[r0, c1] - integral[r1, c0] + integral[r0, c0]
    assert total == image[r0:r1, c0:c1].sum()


def test_haar_features_ignore_the_light_level() -> None:
    rng = np.random.default_rng(0)
    image, window = face_view(face_identity("Ada"), rng, light=0.0, noise=0.0)
    bank = HaarFeatures(50)
    dim = (image.astype(float) * 0.6).astype(np.uint8)
    bright, darker = (bank.compute(integral_image(i), np.asarray([window])) for i in (image, dim))
    assert np.allclose(bright, darker, atol=0.15)
    some = bank.compute(integral_image(image), np.asarray([window]), only=np.array([3, 7]))
    assert np.allclose(some, bright[:, [3, 7]])


def test_the_brightness_plane_is_taken_off_with_the_moments() -> None:
    """A light from one side (a ramp across the image) leaves the features as they were
    when the best-fit plane is taken off; the contrast alone does not."""
    rng = np.random.default_rng(0)
    image, window = face_view(face_identity("Ada"), rng, light=0.0, noise=0.0)
    rows, columns = np.indices(image.shape)
    lit = image + 0.9 * columns - 0.4 * rows + 20.0  # float: no clipping
    bank = HaarFeatures(50, inset=0.12)
    windows = np.asarray([window, (window[0] + 2, window[1] + 1, window[2] - 4)])

    def features(picture: np.ndarray, flat: bool) -> np.ndarray:
        moments = moment_integrals(picture) if flat else None
        return bank.compute(integral_image(picture), windows, core=0.2, moments=moments)

    assert np.allclose(features(image, True), features(lit, True), atol=1e-9)
    assert not np.allclose(features(image, False), features(lit, False), atol=0.05)


def test_the_cascade_finds_a_new_face(detector: FaceDetector) -> None:
    rng = np.random.default_rng(6)
    hits = 0
    for index in range(10):
        image, (x, y, side) = face_view(face_identity(f"new{index}"), rng)
        found = detector.detect(image)
        hits += bool(found) and abs(found[0].x - x) <= side // 3 and \
            abs(found[0].y - y) <= side // 3
    assert hits >= 8


def test_the_refiner_moves_the_window_onto_the_face(detector: FaceDetector) -> None:
    rng = np.random.default_rng(8)
    views = [face_view(face_identity(f"other{index}"), rng) for index in range(20)]
    overlaps = {}
    refine = detector.refine
    try:
        for passes in (0, refine):
            detector.refine = passes
            overlaps[passes] = [_overlap(found[0].window(), window) if found else 0.0
                                for image, window in views
                                for found in [detector.detect(image)]]
    finally:
        detector.refine = refine
    assert refine > 0
    assert np.mean(overlaps[refine]) > np.mean(overlaps[0]) + 0.02
    assert np.median(overlaps[refine]) > 0.8
    # the finer refiner, trained on where the first one leaves windows, moves them closer
    refiners = detector._refiners
    assert len(refiners) == 1 + detector.fine >= 2
    try:
        detector._refiners = refiners[:1]
        first = [_overlap(found[0].window(), window) if found else 0.0
                 for image, window in views for found in [detector.detect(image)]]
    finally:
        detector._refiners = refiners
    assert np.mean(overlaps[refine]) > np.mean(first)


def test_enrolled_people_are_told_apart(detector: FaceDetector) -> None:
    rng = np.random.default_rng(7)
    people = [face_identity(name) for name in ("Ada", "Ben", "Cy")]
    memory = FaceMemory(detector, threshold=math.inf, trees=30)
    with pytest.raises(FaceError):
        memory.identify(face_view(people[0], rng)[0])
    for person in people:
        assert memory.enrol(person.name, [face_view(person, rng)[0] for _ in range(12)]) >= 10
    assert memory.people == ["Ada", "Ben", "Cy"]
    right = sum(memory.identify(face_view(person, rng)[0])[0] == person.name
                for person in people for _ in range(6))
    assert right >= 14
    # strangers are further from anyone's enrolled views than those people's own faces
    # (by distance alone here: no strangers' faces learnt)
    memory.threshold = 1.0
    strangers = [memory.identify(face_view(face_identity(f"x{i}", 3), rng)[0])
                 for i in range(10)]
    known = [(memory.identify(face_view(person, rng)[0]), person.name)
             for person in people for _ in range(4)]
    assert np.median([far for _, far in strangers]) > np.median([far for (_, far), _ in known])
    assert sum(name is None for name, _ in strangers) >= 4
    assert sum(name == truth for (name, _), truth in known) >= 8


def test_enrolment_needs_a_name_and_a_face(detector: FaceDetector) -> None:
    memory = FaceMemory(detector)
    with pytest.raises(FaceError):
        memory.enrol(" ", [])
    with pytest.raises(FaceError, match="no face"):
        memory.enrol("Ada", [np.zeros((80, 80), dtype=np.uint8)])


def test_an_untrained_detector_says_so() -> None:
    with pytest.raises(FaceError, match="not trained"):
        FaceDetector().detect(np.zeros((80, 80), dtype=np.uint8))


def test_a_look_weighs_its_views_together(detector: FaceDetector) -> None:
    rng = np.random.default_rng(11)
    people = [face_identity(name, 4) for name in ("Ada", "Ben", "Cy", "Dee")]
    memory = FaceMemory(detector, trees=40, features=800)
    crowd = [face_identity(f"s{index}", 8) for index in range(12)]
    memory.enrol_strangers([face_view(face, rng)[0] for face in crowd for _ in range(6)],
                           [face.name for face in crowd for _ in range(6)])
    for person in people:
        memory.enrol(person.name, [face_view(person, rng)[0] for _ in range(12)])
    named = [memory.identify_views([face_view(person, rng)[0] for _ in range(6)])
             for person in people for _ in range(3)]
    truth = [person.name for person in people for _ in range(3)]
    # a known person's look may come out unknown, never as someone else
    assert all(name in (None, right) for name, right in zip(named, truth, strict=True))
    assert sum(name == right for name, right in zip(named, truth, strict=True)) >= 7
    # a stranger's look is named less often than a stranger's single view (this small
    # cascade's windows wander: its strangers are named more often than the bench's)
    looks = [[face_view(face_identity(f"x{i}", 5), rng)[0] for _ in range(6)]
             for i in range(30)]
    by_look = sum(memory.identify_look(views)[0] is not None for views in looks) / 30
    by_view = sum(memory.identify(view)[0] is not None for views in looks
                  for view in views) / 180
    assert by_look < 0.8 * by_view
    assert memory.identify_look([np.zeros((80, 80), dtype=np.uint8)]) == (None, math.inf)
    # the look's threshold is learnt from the enrolment: narrower for more views
    assert memory._look_threshold(6) < memory._look_threshold(1)


def test_faces_of_strangers_learnt_make_newcomers_nobody_known(
        detector: FaceDetector) -> None:
    people = [face_identity(name, 6) for name in ("Ada", "Ben", "Cy", "Dee")]
    crowd = [face_identity(f"s{index}", 7) for index in range(12)]
    rng = np.random.default_rng(12)
    enrolment = {person.name: [face_view(person, rng)[0] for _ in range(12)]
                 for person in people}
    crowd_views = [face_view(face, rng)[0] for face in crowd for _ in range(4)]
    # newcomers are neither the household nor the strangers learnt
    newcomers = [face_view(face_identity(f"n{index}", 8), rng)[0] for index in range(40)]
    household = [(face_view(person, rng)[0], person.name) for person in people
                 for _ in range(8)]
    outcome = {}
    for learnt in (False, True):
        memory = FaceMemory(detector, trees=40, features=800)
        if learnt:
            assert memory.enrol_strangers(crowd_views, [face.name for face in crowd
                                                        for _ in range(4)]) >= 40
        for name, views in enrolment.items():
            memory.enrol(name, views)
        assert memory.people == ["Ada", "Ben", "Cy", "Dee"]
        outcome[learnt] = (
            sum(memory.identify(view)[0] is None for view in newcomers),
            sum(memory.identify(view)[0] == name for view, name in household))
    # against strangers' faces, a newcomer's nearness to someone is judged better
    assert outcome[True][0] > outcome[False][0]
    assert outcome[True][0] >= 24 and outcome[True][1] >= 16


def test_strangers_need_one_name_per_image_or_none(detector: FaceDetector) -> None:
    memory = FaceMemory(detector, trees=10, features=200)
    views = [face_view(face_identity("s1"), np.random.default_rng(1))[0] for _ in range(2)]
    with pytest.raises(FaceError, match="one name per image"):
        memory.enrol_strangers(views, ["s1"])
    assert memory.enrol_strangers(views) == 2


def test_the_compiled_forest_walk_reaches_the_leaves_scikit_learn_does() -> None:
    from sklearn.ensemble import RandomForestClassifier

    from homebot.perception.faces import _Forest
    from homebot.perception.forest_walk import walk

    rng = np.random.default_rng(3)
    data = rng.normal(size=(300, 12)).astype(np.float32)
    labels = (data[:, 0] + data[:, 3] * data[:, 5] > 0).astype(int) + (data[:, 7] > 1)
    grown = RandomForestClassifier(n_estimators=15, random_state=0).fit(data, labels)
    forest = _Forest.of(grown, 3)
    # scikit-learn compares float32 features: the probes are float32 values
    probes = np.vstack([rng.normal(size=(40, 12)).astype(np.float32), data[:10]])
    expected = grown.apply(probes)  # (probes, trees): each tree's leaf
    plain = getattr(walk, "py_func", walk)
    for vector, leaves in zip(probes.astype(np.float64), expected, strict=True):
        assert np.array_equal(forest.leaves(vector), leaves)
        assert np.array_equal(plain(forest.feature, forest.threshold, forest.left,
                                    forest.right, vector), leaves)


def test_a_person_enrolled_from_one_image_has_a_finite_reach(detector: FaceDetector) -> None:
    rng = np.random.default_rng(14)
    crowd = [face_identity(f"s{index}", 9) for index in range(6)]
    ada = face_identity("Ada", 9)
    for strangers in (False, True):
        memory = FaceMemory(detector, trees=20, features=400)
        if strangers:
            memory.enrol_strangers([face_view(face, rng)[0] for face in crowd for _ in range(3)],
                                   [face.name for face in crowd for _ in range(3)])
        image = face_view(ada, rng)[0]
        assert memory.enrol("Ada", [image]) == 1
        assert 0.0 < memory._reach < math.inf
        assert memory.identify(image)[0] == "Ada"  # the very view it learnt
