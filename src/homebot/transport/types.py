"""ROS 2 message types as cyclonedds structs, generated from rosbags' typestore, never retyped.

``MessageTypes`` reads a ROS 2 distribution's message definitions from the ``rosbags``
typestore (Humble by default) and builds, on first use, a cyclonedds ``IdlStruct`` per
type, named as ROS 2's middleware names it on the wire (``sensor_msgs::msg::dds_::
LaserScan_``). Field order, types, bounds and arrays come from the typestore's field
lists, so the CDR bytes are those of a ROS 2 node (checked against ``rosbags``'
serialiser in tests).

Packages the typestore lacks are registered from their upstream definition text:
``nav2_msgs/action/NavigateToPose`` (Nav2, Humble) and homebot's own interfaces
(``homebot_msgs``). An action ``pkg/action/Name`` is expanded as ``rosidl`` expands it:
``Name_Goal``, ``Name_Result``, ``Name_Feedback``, ``Name_SendGoal_{Request,Response}``,
``Name_GetResult_{Request,Response}`` and ``Name_FeedbackMessage``; a service
``pkg/srv/Name`` into ``Name_Request`` and ``Name_Response``.

Service samples on the wire carry rmw_cyclonedds' request header first (the client's
writer GUID, 8 bytes, and a sequence number, 8 bytes): ``request_struct`` /
``reply_struct`` give those wire types, with the fields ``client_guid`` and ``sequence``
ahead of the service's own.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

from cyclonedds.idl import IdlMeta, IdlStruct  # type: ignore[attr-defined]
from cyclonedds.idl import types as idl_types
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from rosbags.typesys.store import Typestore

from homebot.transport.definitions import ACTIONS, MESSAGES, SERVICES

__all__ = ["MessageTypes", "dds_type_name"]

# cyclonedds' annotation types are indexed at run time (``sequence[float32]``); mypy cannot.
idl: Any = idl_types

# rosbags' node types (rosbags.typesys.base.Nodetype): a base type, a named type, an array
# of fixed length, a sequence.
_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4

_PRIMITIVES: dict[str, Any] = {
    "bool": bool, "byte": idl.byte, "octet": idl.byte, "char": idl.uint8,
    "int8": idl.int8, "uint8": idl.uint8, "int16": idl.int16, "uint16": idl.uint16,
    "int32": idl.int32, "uint32": idl.uint32, "int64": idl.int64, "uint64": idl.uint64,
    "float32": idl.float32, "float64": idl.float64,
}
_DEFAULTS: dict[str, Callable[[], Any]] = {
    "bool": bool, "string": str, "float32": float, "float64": float,
}
_BYTES = {"byte", "octet", "uint8", "char"}
# ``uint8[]`` (image and point cloud data): declared ``sequence<uint8>`` for the type's
# XTypes description, but serialised from and to ``bytes`` at once (``_fast_bytes``).
_BYTE_SEQUENCE = idl.sequence[idl.uint8]


def dds_type_name(ros_name: str) -> str:
    """``pkg/msg/Type`` -> ``pkg::msg::dds_::Type_``, as ROS 2's middleware names it."""
    package, kind, name = ros_name.split("/")
    return f"{package}::{kind}::dds_::{name}_"


def _expand_action(name: str, goal: str, result: str, feedback: str) -> dict[str, str]:
    """The message definitions rosidl generates for an action ``pkg/action/Name``."""
    return {
        f"{name}_Goal": goal, f"{name}_Result": result, f"{name}_Feedback": feedback,
        f"{name}_SendGoal_Request": f"unique_identifier_msgs/UUID goal_id\n{name}_Goal goal",
        f"{name}_SendGoal_Response": "bool accepted\nbuiltin_interfaces/Time stamp",
        f"{name}_GetResult_Request": "unique_identifier_msgs/UUID goal_id",
        f"{name}_GetResult_Response": f"int8 status\n{name}_Result result",
        f"{name}_FeedbackMessage":
            f"unique_identifier_msgs/UUID goal_id\n{name}_Feedback feedback",
    }


def _split(definition: str, parts: int) -> list[str]:
    pieces = [piece.strip("\n") for piece in definition.split("\n---\n")]
    if len(pieces) != parts:  # pragma: no cover - the shipped definitions are checked in tests
        raise ValueError(f"an interface definition with {parts} parts, got {len(pieces)}")
    return pieces


class MessageTypes:
    """The ROS 2 types of one distribution, as cyclonedds structs made on demand."""

    def __init__(self, store: Stores = Stores.ROS2_HUMBLE) -> None:
        self.store: Typestore = get_typestore(store)
        definitions: dict[str, str] = dict(MESSAGES)
        for name, text in SERVICES.items():
            request, response = _split(text, 2)
            definitions[f"{name}_Request"] = request
            definitions[f"{name}_Response"] = response
        for name, text in ACTIONS.items():
            definitions.update(_expand_action(name, *_split(text, 3)))
        for name, text in definitions.items():
            # rosbags files a ``pkg/srv/Name`` definition under ``pkg/srv/msg/Name``.
            self.store.register({key.replace("/srv/msg/", "/srv/"): value
                                 for key, value in get_types_from_msg(text, name).items()})
        self._structs: dict[str, type[Any]] = {}
        self._wire: dict[tuple[str, str], type[Any]] = {}

    def struct(self, name: str) -> type[Any]:
        """The cyclonedds struct of ``pkg/msg/Type`` (made once, then cached)."""
        made = self._structs.get(name)
        if made is None:
            fields = self._fields(name)
            made = _make_struct(name.replace("/", "_"), dds_type_name(name), fields)
            self._structs[name] = made
        return made

    def request_struct(self, service: str) -> type[Any]:
        """The wire type of a service's (or action sub-service's) request, header first."""
        return self._with_header(service, "Request")

    def reply_struct(self, service: str) -> type[Any]:
        """The wire type of a service's (or action sub-service's) reply, header first."""
        return self._with_header(service, "Response")

    def new(self, name: str, /, **values: Any) -> Any:
        """A message of type ``name`` with ``values``, every other field at its default."""
        return self.struct(name)(**values)

    def _with_header(self, service: str, part: str) -> type[Any]:
        made = self._wire.get((service, part))
        if made is None:
            fields: dict[str, tuple[Any, Any]] = {
                "client_guid": (idl.uint64, int), "sequence": (idl.int64, int),
                      **self._fields(f"{service}_{part}")}
            made = _make_struct(f"{service}_{part}".replace("/", "_") + "_wire",
                                dds_type_name(f"{service}_{part}"), fields)
            self._wire[(service, part)] = made
        return made

    def _fields(self, name: str) -> dict[str, tuple[Any, Any]]:
        try:
            _constants, fields = self.store.fielddefs[name]
        except KeyError:
            raise KeyError(f"no ROS 2 type {name} in the typestore") from None
        return {field: self._field(spec) for field, spec in fields}

    def _field(self, spec: tuple[int, Any]) -> tuple[Any, Any]:
        """The cyclonedds annotation and the default factory of one typestore field."""
        kind, detail = spec
        if kind == _BASE:
            base, bound = detail
            if base == "string":
                return (idl.bounded_str[bound] if bound else str), str
            return _PRIMITIVES[base], _DEFAULTS.get(base, int)
        if kind == _NAME:
            struct = self.struct(detail)
            return struct, struct
        (inner_kind, inner), length = detail
        if inner_kind == _BASE and inner[0] in _BYTES and inner[0] != "char":
            if kind == _ARRAY:
                return idl.array[idl.uint8, length], lambda: bytes(length)
            if not length:
                return _BYTE_SEQUENCE, bytes
        element, element_default = self._field((inner_kind, inner))
        if kind == _ARRAY:
            return idl.array[element, length], lambda: [element_default()
                                                        for _ in range(length)]
        return (idl.sequence[element, length] if length else idl.sequence[element]), list


def _make_struct(class_name: str, typename: str,
                 fields: dict[str, tuple[Any, Any]]) -> type[Any]:
    """``cyclonedds.idl.make_idl_struct`` with a default for every field."""
    namespace: Any = IdlMeta.__prepare__(class_name, (IdlStruct,), typename=typename)
    for field, (annotation, default) in fields.items():
        namespace["__annotations__"][field] = annotation
        namespace[field] = dataclasses.field(default_factory=default)
    made: Any = IdlMeta(class_name, (IdlStruct,), namespace)  # type: ignore[no-untyped-call]
    made = dataclasses.dataclass(made)
    _fast_bytes(made, [field for field, (annotation, _) in fields.items()
                       if annotation is _BYTE_SEQUENCE])
    return made  # type: ignore[no-any-return]


def _fast_bytes(struct: Any, fields: list[str]) -> None:
    """Serialise the ``uint8[]`` fields of ``struct`` as ``bytes`` (one copy, not one Python
    int per byte): the same CDR (a 32-bit length, then the bytes) in XCDR1 and XCDR2."""
    if not fields:
        return
    from cyclonedds.idl._machinery import BytesMachine

    struct.__idl__.populate()
    for machine in (struct.__idl__.v1_machine, struct.__idl__.v2_machine):
        members = getattr(machine, "members_machines", None)
        if members is not None:
            for field in fields:
                members[field] = BytesMachine()  # type: ignore[no-untyped-call]
