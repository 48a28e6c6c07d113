"""The simulator: seeded disturbances, sensors that can be wrong, ground truth kept apart."""

from __future__ import annotations

import math

from shapely.geometry import Point as ShapelyPoint

from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.robot import Blocker
from homebot.sim import ScriptedResponder, SimRobot, Simulation
from homebot.world import DisturbanceModel, DoorState, World

EVERYTHING = DisturbanceModel(object_moved=0.3, object_missing=0.1, door_closed=0.4,
                              person_in_way=0.2)


def test_same_seed_same_disturbances(apartment: World, apartment_navigator: Navigator) -> None:
    first = Simulation(apartment, seed=7, disturbances=EVERYTHING, navigator=apartment_navigator)
    second = Simulation(apartment, seed=7, disturbances=EVERYTHING,
                        navigator=apartment_navigator)
    other = Simulation(apartment, seed=8, disturbances=EVERYTHING, navigator=apartment_navigator)
    assert first.events.to_json_lines() == second.events.to_json_lines()
    assert first.object_location == second.object_location
    assert first.events.to_json_lines() != other.events.to_json_lines()


def test_no_disturbances_means_truth_is_the_world_file(apartment: World,
                                                       apartment_navigator: Navigator) -> None:
    simulation = Simulation(apartment, seed=1, navigator=apartment_navigator)
    assert simulation.object_location == {n: o.placement for n, o in apartment.objects.items()}
    assert simulation.closed_doors() == frozenset()


def test_moving_takes_simulated_time_by_path_length(apartment: World,
                                                    apartment_navigator: Navigator) -> None:
    simulation = Simulation(apartment, seed=1, navigator=apartment_navigator)
    robot = SimRobot(simulation)
    report = robot.move_to(apartment.placements["fridge"].approach)
    assert report.reached
    assert simulation.clock.now() >= report.distance / apartment.robot.speed
    assert robot.pose().xy() == apartment.placements["fridge"].approach.xy()


def test_a_closed_door_stops_the_robot_in_front_of_it(apartment: World,
                                                      apartment_navigator: Navigator) -> None:
    simulation = Simulation(apartment, seed=1, navigator=apartment_navigator)
    simulation.door_state["bedroom door"] = DoorState.CLOSED
    robot = SimRobot(simulation)
    report = robot.move_to(apartment.placements["bed"].approach)
    assert not report.reached
    assert report.blocker is Blocker.DOOR_CLOSED and report.door == "bedroom door"
    assert apartment.room_at(*robot.pose().xy()) == "corridor"


def test_a_person_in_a_doorway_blocks_until_asked(apartment: World,
                                                  apartment_navigator: Navigator) -> None:
    simulation = Simulation(apartment, seed=1, navigator=apartment_navigator)
    simulation.place_person_in_doorway("office door", "Maria")
    robot = SimRobot(simulation)
    report = robot.move_to(apartment.placements["desk"].approach)
    assert report.blocker is Blocker.PERSON and report.person == "Maria"
    from homebot.robot import HelpRequest

    assert robot.request("Maria", HelpRequest.STEP_ASIDE, "office door")
    assert robot.move_to(apartment.placements["desk"].approach).reached


def test_a_request_to_nobody_by_name_is_heard_by_whoever_stands_in_the_door(
        apartment: World, apartment_navigator: Navigator) -> None:
    from homebot.robot import HelpRequest

    simulation = Simulation(apartment, seed=1, navigator=apartment_navigator)
    visitor = simulation.place_person_in_doorway("office door")
    robot = SimRobot(simulation)
    assert not robot.move_to(apartment.placements["desk"].approach).reached
    assert robot.request("", HelpRequest.STEP_ASIDE, "office door")
    assert simulation.people[visitor].blocking_door is None
    assert robot.move_to(apartment.placements["desk"].approach).reached


def test_someone_stepping_out_of_a_doorway_stands_on_free_floor_off_the_robots_way(
        apartment: World, apartment_navigator: Navigator) -> None:
    from homebot.robot import HelpRequest

    simulation = Simulation(apartment, seed=1, navigator=apartment_navigator)
    visitor = simulation.place_person_in_doorway("kitchen door")
    robot = SimRobot(simulation)
    assert robot.move_to(Pose(9.5, 5.0, -1.57)).person == visitor  # they block the door
    assert robot.request("", HelpRequest.STEP_ASIDE, "kitchen door")
    spot = simulation.people[visitor].position
    # not into the kitchen's middle (under its table), nor next to the robot
    assert apartment.footprint_problem(*spot, radius=0.15) is None
    assert simulation.distance_to(spot) >= 1.0
    assert robot.move_to(Pose(9.5, 5.0, -1.57)).reached


def test_grasp_needs_reach_and_can_slip(apartment: World, apartment_navigator: Navigator) -> None:
    slippery = DisturbanceModel(grasp_slip=1.0)
    simulation = Simulation(apartment, seed=1, disturbances=slippery,
                            navigator=apartment_navigator)
    robot = SimRobot(simulation)
    robot.move_to(apartment.placements["fridge"].approach)
    cola = next(d for d in robot.perceive_objects("fridge") if d.label == "cola")
    robot.grasp(cola, "left")
    assert robot.held("left") is None
    assert simulation.object_location["cola"] == "fridge"
    simulation.disturbances = DisturbanceModel()
    robot.grasp(cola, "left")
    held = robot.held("left")
    assert held is not None and held.label == "cola"


def test_perception_far_from_a_placement_sees_nothing(apartment: World,
                                                      apartment_navigator: Navigator) -> None:
    robot = SimRobot(Simulation(apartment, seed=1, navigator=apartment_navigator))
    assert robot.perceive_objects("fridge") == []


def test_people_answer_from_the_world_and_the_script(apartment: World) -> None:
    responder = ScriptedResponder({"Alex": {"What is your favourite drink?": "tea"}})
    alex = apartment.person("Alex")
    assert responder(alex, "What would you like to drink?") == "orange juice"
    assert responder(alex, "what is your favourite drink") == "tea"
    assert responder(alex, "What is your name?") == "Alex"
    assert responder(alex, "How is the weather on Mars?") is None


def test_interactive_people_answer_what_is_typed(apartment: World) -> None:
    from homebot.sim import InteractiveResponder

    prompts: list[str] = []

    def typed(prompt: str) -> str:
        prompts.append(prompt)
        return "  lemonade  "

    responder = InteractiveResponder(typed)
    assert responder(apartment.person("Maria"), "What would you like?") == "lemonade"
    assert "Maria" in prompts[0]

    def closed(prompt: str) -> str:
        raise EOFError

    assert InteractiveResponder(closed)(apartment.person("Maria"), "Anything?") is None


def test_a_person_asked_aside_steps_off_the_robots_way(apartment: World,
                                                       apartment_navigator: Navigator) -> None:
    import math

    import numpy as np

    simulation = Simulation(apartment, seed=1, navigator=apartment_navigator)
    grid, clearance = apartment_navigator.grid, apartment_navigator.clearance()
    person = grid.center_of(*np.unravel_index(int(np.argmax(clearance)), clearance.shape))
    for heading in np.linspace(0, 2 * math.pi, 8, endpoint=False):
        robot = (person[0] - 1.2 * math.cos(heading), person[1] - 1.2 * math.sin(heading))
        simulation.robot_pose = (*robot, float(heading))
        spot = simulation.spot_aside(person)
        assert spot is not None
        # Measured across the robot's heading: to the side of its way, not ahead on it.
        along = (spot[0] - robot[0]) * math.cos(heading) + (spot[1] - robot[1]) * math.sin(heading)
        across = -(spot[0] - robot[0]) * math.sin(heading) + \
            (spot[1] - robot[1]) * math.cos(heading)
        assert abs(across) >= 0.9 or along < 0 or along > 1.2 + 2.5
        assert math.dist(spot, robot) >= 1.0


def test_a_person_asked_aside_keeps_off_the_way_the_robot_faces(
        apartment: World, apartment_navigator: Navigator) -> None:
    # The robot faces along the corridor, the person stands off to one side of that line
    # (ahead of it, not straight ahead): they step away from where the robot is going,
    # not onto it.
    import math

    from shapely.geometry import LineString, Point

    simulation = Simulation(apartment, seed=1, navigator=apartment_navigator)
    simulation.robot_pose = (9.4, 5.0, math.pi)  # in the corridor, facing west along it
    person = (8.4, 4.6)
    spot = simulation.spot_aside(person)
    assert spot is not None
    faced = LineString([(9.4, 5.0), (9.4 - 3.6, 5.0)])
    assert faced.distance(Point(spot)) >= 0.9


def test_objects_put_on_a_surface_stand_apart_on_it(apartment: World,
                                                    apartment_navigator: Navigator) -> None:
    # Moved by people (disturbances, walkers), not stacked on its centre: the camera would
    # see two objects in one place as one.
    simulation = Simulation(apartment, seed=1, navigator=apartment_navigator)
    table = apartment.placements["side table"]
    for name in ("banana", "soap", "cola"):
        simulation.put_object(name, "side table")
    spots = [simulation.position_on(name, "side table") for name in simulation.objects_on(
        "side table")]
    assert len(spots) >= 4  # the candle was there already
    for spot in spots:
        assert table.footprint.covers(ShapelyPoint(spot))
    gaps = [math.dist(a, b) for i, a in enumerate(spots) for b in spots[i + 1:]]
    assert min(gaps) > 0.12


_DINING_OFF_A_CORRIDOR = """
name: dining_beside_a_kitchen
rooms:
  - {name: corridor, polygon: [[0, 3], [8, 3], [8, 4], [0, 4]]}
  - {name: kitchen, polygon: [[0, 0], [3.5, 0], [3.5, 3], [0, 3]]}
  - {name: dining room, polygon: [[3.5, 0], [7, 0], [7, 3], [3.5, 3]]}
doors:
  - {name: kitchen door, rooms: [kitchen, corridor], position: [2.8, 3], width: 0.8}
  - {name: dining room door, rooms: [dining room, corridor], position: [4.2, 3], width: 0.8}
placements:
  - {name: sideboard, category: storage, room: dining room, center: [3.75, 1.3],
     size: [0.45, 1.2]}
  - {name: dining table, category: table, room: dining room, center: [5.7, 1.3],
     size: [1.4, 0.9]}
people:
  - {name: Mei, room: dining room, position: [4.5, 2.3]}
robot:
  pose: [4.07, 2.58, -0.91]
"""


def test_someone_asked_aside_steps_aside_in_their_own_room() -> None:
    # Just inside the dining-room door (as in benchmarks/flats/flat_narrow): the open floor
    # behind the kitchen wall is no spot to step to; the walk there runs round through the
    # doorway the robot stands in, and she stood still, asked four times.
    world = World.from_yaml_text(_DINING_OFF_A_CORRIDOR)
    simulation = Simulation(world, seed=1, navigator=Navigator(world))
    spot = simulation.spot_aside(simulation.people["Mei"].position)
    assert spot is not None and world.room_at(*spot) == "dining room"
    assert math.dist(spot, simulation.robot_pose[:2]) >= 1.0
