"""Wire format: type names and CDR bytes equal those rosbags gives for the same ROS 2 type."""

from __future__ import annotations

import random
from typing import Any

import pytest

pytest.importorskip("cyclonedds")
pytest.importorskip("rosbags")

import numpy as np

from homebot.transport.types import MessageTypes, dds_type_name

MESSAGES = [
    "std_msgs/msg/String", "std_msgs/msg/Header",
    "geometry_msgs/msg/Twist", "geometry_msgs/msg/PoseStamped",
    "geometry_msgs/msg/PoseWithCovarianceStamped",
    "nav_msgs/msg/Odometry", "nav_msgs/msg/OccupancyGrid", "nav_msgs/msg/Path",
    "sensor_msgs/msg/LaserScan", "sensor_msgs/msg/PointCloud2", "sensor_msgs/msg/Image",
    "sensor_msgs/msg/JointState", "tf2_msgs/msg/TFMessage",
    "action_msgs/msg/GoalStatusArray",
    "nav2_msgs/action/NavigateToPose_Goal", "nav2_msgs/action/NavigateToPose_Feedback",
    "nav2_msgs/action/NavigateToPose_Result", "nav2_msgs/action/NavigateToPose_FeedbackMessage",
]
SERVICES = [
    "nav2_msgs/action/NavigateToPose_SendGoal", "nav2_msgs/action/NavigateToPose_GetResult",
    "action_msgs/srv/CancelGoal", "homebot_msgs/srv/RobotCall", "homebot_msgs/srv/Parse",
]
_INTS = {"int8": (-128, 127), "uint8": (0, 255), "byte": (0, 255), "char": (0, 255),
         "int16": (-2**15, 2**15 - 1), "uint16": (0, 2**16 - 1), "int32": (-2**31, 2**31 - 1),
         "uint32": (0, 2**32 - 1), "int64": (-2**63, 2**63 - 1), "uint64": (0, 2**64 - 1)}
_DTYPES = {"float32": np.float32, "float64": np.float64, "bool": np.bool_, "byte": np.uint8,
           "char": np.uint8, **{name: getattr(np, name) for name in _INTS
                                if name not in ("byte", "char")}}


@pytest.fixture(scope="module")
def types() -> MessageTypes:
    return MessageTypes()


def _value(types: MessageTypes, spec: tuple[int, Any], rng: random.Random) -> Any:
    """Random content for one field, as plain Python (lists for sequences)."""
    kind, detail = spec
    if kind == 1:
        base, bound = detail
        if base == "string":
            return "".join(rng.choice("abcxyz/_é") for _ in range(rng.randint(0, bound or 9)))
        if base == "bool":
            return rng.random() < 0.5
        if base in _INTS:
            return rng.randint(*_INTS[base])
        value = rng.uniform(-1e3, 1e3)
        return float(np.float32(value)) if base == "float32" else value
    if kind == 2:
        return _content(types, detail, rng)
    inner, length = detail
    count = length if kind == 3 else rng.randint(0, 5)
    return [_value(types, inner, rng) for _ in range(count)]


def _content(types: MessageTypes, name: str, rng: random.Random) -> dict[str, Any]:
    _constants, fields = types.store.fielddefs[name]
    return {field: _value(types, spec, rng) for field, spec in fields}


def _to_dds(types: MessageTypes, name: str, content: dict[str, Any]) -> Any:
    values = {}
    for field, spec in types.store.fielddefs[name][1]:
        value = content[field]
        if spec[0] == 2:
            value = _to_dds(types, spec[1], value)
        elif spec[0] in (3, 4):
            inner = spec[1][0]
            if inner[0] == 2:
                value = [_to_dds(types, inner[1], item) for item in value]
            elif inner[0] == 1 and inner[1][0] in ("uint8", "byte"):
                value = bytes(value)
        values[field] = value
    return types.new(name, **values)


def _to_rosbags(types: MessageTypes, name: str, content: dict[str, Any]) -> Any:
    values = {}
    for field, spec in types.store.fielddefs[name][1]:
        value = content[field]
        if spec[0] == 2:
            value = _to_rosbags(types, spec[1], value)
        elif spec[0] in (3, 4):
            inner = spec[1][0]
            if inner[0] == 2:
                value = [_to_rosbags(types, inner[1], item) for item in value]
            elif inner[0] == 1 and inner[1][0] != "string":
                value = np.array(value, dtype=_DTYPES[inner[1][0]])
        values[field] = value
    return types.store.types[name](**values)


@pytest.mark.parametrize("name", MESSAGES)
def test_the_cdr_bytes_are_rosbags_own(types: MessageTypes, name: str) -> None:
    for seed in range(3):
        content = _content(types, name, random.Random(seed))
        ours = _to_dds(types, name, content).serialize()
        theirs = bytes(types.store.serialize_cdr(_to_rosbags(types, name, content), name))
        assert ours == theirs
        assert types.struct(name).deserialize(theirs) == _to_dds(types, name, content)


@pytest.mark.parametrize("name", MESSAGES)
def test_the_dds_type_name_is_ros2s(types: MessageTypes, name: str) -> None:
    package, kind, short = name.split("/")
    assert types.struct(name).__idl_typename__ == f"{package}::{kind}::dds_::{short}_"
    assert dds_type_name(name) == f"{package}::{kind}::dds_::{short}_"


@pytest.mark.parametrize("service", SERVICES)
@pytest.mark.parametrize("part", ["Request", "Response"])
def test_service_samples_are_rmw_cyclonedds_header_then_the_message(
        types: MessageTypes, service: str, part: str) -> None:
    name = f"{service}_{part}"
    content = _content(types, name, random.Random(7))
    wire = (types.request_struct if part == "Request" else types.reply_struct)(service)
    sample = wire(client_guid=2**64 - 3, sequence=41, **vars(_to_dds(types, name, content)))
    data = sample.serialize()
    theirs = bytes(types.store.serialize_cdr(_to_rosbags(types, name, content), name))
    assert data[:4] == theirs[:4]  # the same encapsulation (CDR, little endian)
    assert data[4:20] == (2**64 - 3).to_bytes(8, "little") + (41).to_bytes(8, "little")
    assert data[20:] == theirs[4:]
    assert wire.__idl_typename__ == dds_type_name(name)


def test_the_map_and_the_laser_keep_their_fields_in_rosbags_order(types: MessageTypes) -> None:
    scan = types.new("sensor_msgs/msg/LaserScan", ranges=[1.0, float("inf")], range_max=10.0)
    back = types.store.deserialize_cdr(scan.serialize(), "sensor_msgs/msg/LaserScan")
    assert back.range_max == 10.0 and back.ranges[0] == 1.0 and np.isinf(back.ranges[1])
