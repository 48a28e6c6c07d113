"""Table-top perception: RANSAC support plane, clustering, features, recognition, estimates."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("sklearn")

from homebot.app.perception import labelled_frames
from homebot.perception.recognition import (
    Recogniser,
    TabletopPerception,
    match_positions,
    training_examples,
)
from homebot.perception.tabletop import (
    FEATURE_NAMES,
    cluster,
    cluster_features,
    row_spacing,
    segment_plane,
    segment_tabletop,
)
from homebot.robot import HeadState, RgbdFrame
from homebot.sim.camera import CAMERA_HEIGHT, CameraSimulator, SceneGeometry, Solid
from homebot.sim.tabletop import tabletop_scene
from homebot.world import CatalogueEntry, Shape

CATALOGUE = {
    "can": CatalogueEntry("can", "drink", Shape.CYLINDER, (0.07, 0.2), "red", (200, 30, 30),
                          0.4),
    "box": CatalogueEntry("box", "food", Shape.BOX, (0.07, 0.15, 0.2), "green", (40, 160, 60),
                          0.5),
    "ball": CatalogueEntry("ball", "toy", Shape.SPHERE, (0.09,), "yellow", (230, 210, 40),
                           0.1),
    "plate": CatalogueEntry("plate", "dish", Shape.CYLINDER, (0.16, 0.04), "white",
                            (235, 235, 235), 0.3),
}


def test_ransac_finds_the_horizontal_plane_not_the_bigger_wall() -> None:
    rng = np.random.default_rng(0)
    table = np.column_stack((rng.uniform(0, 1, 2000), rng.uniform(-0.5, 0.5, 2000),
                             0.75 + 0.001 * rng.standard_normal(2000)))
    wall = np.column_stack((np.full(5000, 1.2), rng.uniform(-1, 1, 5000),
                            rng.uniform(0, 2, 5000)))
    model, inliers = segment_plane(np.vstack((table, wall)), 0.01, 60, rng)
    assert model[2] == pytest.approx(0.75, abs=0.002)
    assert abs(model[0]) < 0.01 and abs(model[1]) < 0.01
    assert set(inliers.tolist()) >= set(range(1950))
    assert np.count_nonzero(inliers >= 2000) < 100  # only where the wall crosses it


def test_cluster_groups_by_distance_and_drops_small_groups() -> None:
    rng = np.random.default_rng(1)
    first = rng.normal((0, 0, 0), 0.004, (100, 3))
    second = rng.normal((0.3, 0, 0), 0.004, (80, 3))
    speck = rng.normal((0, 0.5, 0), 0.001, (3, 3))
    labels = cluster(np.vstack((first, second, speck)), 0.02, 10)
    assert len(set(labels[:100])) == 1 and len(set(labels[100:180])) == 1
    assert labels[0] != labels[100] and set(labels[180:]) == {-1}


def test_segments_lie_where_the_objects_stand() -> None:
    rng = np.random.default_rng(5)
    scene = tabletop_scene(list(CATALOGUE.values()), 4, rng)
    tabletop = segment_tabletop(scene.frame, rng)
    assert tabletop.plane is not None
    assert tabletop.plane.c == pytest.approx(scene.surface, abs=0.01)
    positions = [segment.position() for segment in tabletop.segments]
    pairs = match_positions(positions, [placed.position for placed in scene.objects])
    assert len(pairs) == len(scene.objects) == len(positions)
    for found, truth in pairs:
        assert np.hypot(*np.subtract(positions[found][:2],
                                     scene.objects[truth].position[:2])) < 0.025
    features = cluster_features(tabletop.segments[0])
    assert features.shape == (len(FEATURE_NAMES),)


def test_a_frame_without_a_table_has_no_objects() -> None:
    rng = np.random.default_rng(2)
    frame = tabletop_scene(list(CATALOGUE.values()), 2, rng).frame
    floor_only = type(frame)(frame.stamp, frame.rgb, np.where(
        frame.depth > 0, np.nan, frame.depth).astype(np.float32), frame.intrinsics,
        frame.camera_pose)
    assert segment_tabletop(floor_only, rng).segments == ()


def test_recognition_trained_on_rendered_views_names_the_objects() -> None:
    rng = np.random.default_rng(3)
    features, labels = training_examples(labelled_frames(CATALOGUE, 8, rng), rng)
    assert set(labels) == set(CATALOGUE)
    perception = TabletopPerception(Recogniser(CATALOGUE).fit(features, labels),
                                    np.random.default_rng(4))
    right = total = 0
    for seed in range(4):
        scene = tabletop_scene(list(CATALOGUE.values()), 3, np.random.default_rng(100 + seed))
        estimates = perception.perceive(scene.frame)
        for found, truth in match_positions([e.position for e in estimates],
                                            [p.position for p in scene.objects]):
            total += 1
            right += estimates[found].label == scene.objects[truth].entry.name
            assert estimates[found].category == CATALOGUE[estimates[found].label].category
    assert total >= 10 and right / total >= 0.9


def test_an_untrained_recogniser_says_object() -> None:
    rng = np.random.default_rng(6)
    scene = tabletop_scene(list(CATALOGUE.values()), 2, rng)
    estimates = TabletopPerception(Recogniser(CATALOGUE), rng).perceive(scene.frame)
    assert estimates and {e.category for e in estimates} == {"object"}


def test_points_seen_edge_on_reach_farther_neighbours() -> None:
    strips = np.array([(x, y, 1.25) for x in (0.6, 0.625, 0.65)
                       for y in np.arange(0, 0.1, 0.005)])
    assert len(set(cluster(strips, 0.016, 5).tolist())) == 3  # rows 2.5 cm apart: three
    spacing = row_spacing(strips, np.array([0.0, 0.0, 1.3]), 285.0)
    assert np.all(spacing > 0.02)  # 5 cm below the camera, the rows lie far apart
    reach = np.clip(1.4 * spacing, 0.016, 0.04)
    assert len(set(cluster(strips, 0.016, 5, reach).tolist())) == 1


def test_a_ball_is_placed_under_its_crown_not_towards_the_camera() -> None:
    # The camera sees a ball's near side only: centring what it sees of the top pulls
    # the estimate towards the robot (1.2 cm median, 1.2 cm towards the camera, before).
    ball = [CATALOGUE["ball"]]
    errors = []
    for seed in range(12):
        scene = tabletop_scene(ball, 1, np.random.default_rng(200 + seed))
        segments = segment_tabletop(scene.frame, np.random.default_rng(seed)).segments
        assert len(segments) == 1
        errors.append(np.subtract(segments[0].position()[:2], scene.objects[0].position[:2]))
    along_sight = [error[0] for error in errors]  # the camera looks along +x
    assert abs(float(np.median(along_sight))) < 0.003
    assert float(np.median(np.hypot(*np.transpose(errors)))) < 0.004


def _side_by_side(rng: np.random.Generator, first: Solid, second: Solid) -> RgbdFrame:
    """One view of a 0.75 m table from its approach, with two objects on it."""
    table = np.array([[0.35, -0.6, 1.15, 0.6, 0.75]])
    camera = CameraSimulator(SceneGeometry(np.zeros((0, 4)), table), rng)
    head = HeadState(0.0, float(np.arctan2(CAMERA_HEIGHT - 0.75, 0.75)))
    return camera.render(0.0, (0.0, 0.0, 0.0), head, [first, second])


@pytest.mark.parametrize(("first", "second"), [
    # a banana (a green ball) leaning into a white cup: their footprints overlap by 1 cm
    (Solid(Shape.SPHERE, (0.084, 0.084, 0.084), (40, 160, 60), 0.7, -0.05, 0.75),
     Solid(Shape.CYLINDER, (0.156, 0.156, 0.049), (235, 235, 235), 0.7, 0.06, 0.75)),
    # a beige fork (a flat disc) against a grey bowl: hues only 0.16 rad apart
    (Solid(Shape.CYLINDER, (0.144, 0.144, 0.045), (220, 200, 160), 0.7, -0.05, 0.75),
     Solid(Shape.CYLINDER, (0.167, 0.167, 0.052), (128, 128, 128), 0.7, 0.1055, 0.75)),
])
def test_two_objects_that_touch_are_two_segments_by_their_colours(first: Solid,
                                                                  second: Solid) -> None:
    # Distance alone made one 20-29 cm "bowl" of each pair (a banana and a cup were not
    # found in the robustness errands)
    for seed in range(3):
        rng = np.random.default_rng(seed)
        segments = segment_tabletop(_side_by_side(rng, first, second), rng).segments
        positions = [segment.position() for segment in segments]
        truth = [(first.x, first.y), (second.x, second.y)]
        assert len(positions) == 2 and len(match_positions(positions, truth, 0.02)) == 2


def test_one_object_in_shade_and_light_is_not_split_by_its_colours() -> None:
    # a dark brown bottle and a grey bowl apart: lit and shaded sides, and the noise of a
    # dark colour, are one hue each
    bottle = Solid(Shape.CYLINDER, (0.071, 0.071, 0.2), (120, 75, 35), 0.7, -0.12, 0.75)
    bowl = Solid(Shape.CYLINDER, (0.167, 0.167, 0.052), (128, 128, 128), 0.75, 0.1, 0.75)
    for seed in range(6):
        rng = np.random.default_rng(seed)
        segments = segment_tabletop(_side_by_side(rng, bottle, bowl), rng).segments
        assert len(segments) == 2


def test_a_cluster_far_bigger_than_any_object_it_knows_is_no_object() -> None:
    # someone lying on the bed was a 1.4 m "bowl" and a 0.6 m "vase"
    rng = np.random.default_rng(7)
    features, labels = training_examples(labelled_frames(CATALOGUE, 6, rng), rng)
    perception = TabletopPerception(Recogniser(CATALOGUE).fit(features, labels), rng)
    blanket = Solid(Shape.BOX, (0.3, 0.8, 0.2), (235, 235, 235), 0.95, 0.0, 0.75)
    can = Solid(Shape.CYLINDER, (0.07, 0.07, 0.2), (200, 30, 30), 0.6, 0.3, 0.75)
    for seed in range(3):
        estimates = perception.perceive(_side_by_side(np.random.default_rng(seed), blanket, can))
        assert [estimate.label for estimate in estimates] == ["can"]
