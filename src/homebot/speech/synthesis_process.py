"""espeak-ng in a process of its own, which forks a fresh child for each utterance.

Why a process: espeak-ng's Klatt synthesiser keeps state from one utterance to the next (see
``homebot.speech.voice``), so each utterance is synthesised in a forked child of a process
that never synthesises itself. Forking the caller itself is unsafe when the caller has threads
(a test runner's workers, a web server, DDS): the child inherits locks held by threads that do
not exist in it, and espeak-ng's child crashed with a segmentation fault there. This process
is started once (not forked), has one thread, loads espeak-ng once and only forks.

The protocol, on its standard input and output: a request is a 4-byte little-endian length
and a JSON object ``{"op": "synthesise" | "phonemes", "text", "name", "rate", "pitch"}``; a
reply is the child's wait status and a payload length (``<iI``) and the payload (int16 samples,
or UTF-8 IPA). The process says espeak-ng's sample rate once when it starts (``<i``), and exits
when its input closes.
"""

from __future__ import annotations

import json
import os
import struct
import sys
from typing import BinaryIO

__all__ = ["NO_VOICE", "serve"]

NO_VOICE = 3  # a child's exit status: espeak-ng has no such voice
_REQUEST = struct.Struct("<I")
_REPLY = struct.Struct("<iI")
_RATE = struct.Struct("<i")


def _read_exactly(stream: BinaryIO, size: int) -> bytes | None:
    data = b""
    while len(data) < size:
        chunk = stream.read(size - len(data))
        if not chunk:
            return None
        data += chunk
    return data


def _run_in_child(request: dict[str, object]) -> tuple[int, bytes]:
    """The request carried out in a forked child: its wait status and what it wrote."""
    from homebot.errors import SpeechError
    from homebot.speech.voice import VoiceSettings, in_process_voice

    voice = in_process_voice()
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # pragma: no cover - runs in the child, which exits at once
        status = 1
        try:
            os.close(read)
            settings = VoiceSettings(str(request["name"]), int(str(request["rate"])),
                                     int(str(request["pitch"])))
            text = str(request["text"])
            if request["op"] == "phonemes":
                data = voice.phonemes(text, settings).encode("utf-8")
            else:
                data = voice.synthesise_native(text, settings).tobytes()
            view = memoryview(data)
            while view:
                view = view[os.write(write, view):]
            status = 0
        except SpeechError:
            status = NO_VOICE
        finally:
            os._exit(status)
    os.close(write)
    with os.fdopen(read, "rb") as handle:
        data = handle.read()
    _, status = os.waitpid(pid, 0)
    return status, data


def serve(requests: BinaryIO | None = None, replies: BinaryIO | None = None) -> None:
    """Answer requests until the input closes."""
    from homebot.speech.voice import in_process_voice

    requests = requests or sys.stdin.buffer
    replies = replies or sys.stdout.buffer
    replies.write(_RATE.pack(in_process_voice().rate))
    replies.flush()
    while (header := _read_exactly(requests, _REQUEST.size)) is not None:
        body = _read_exactly(requests, _REQUEST.unpack(header)[0])
        if body is None:
            return
        status, data = _run_in_child(json.loads(body))
        replies.write(_REPLY.pack(status, len(data)) + data)
        replies.flush()
