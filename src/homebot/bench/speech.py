"""Speech: spoken commands heard by the two reconciled decoders, clean and noisy; rejection.

espeak-ng speaks commands that ``homebot.language.generator`` writes for the apartment and
for the RoboCup@Home template world (``--robocup``), cycling through four voices and speeds
(``homebot.speech.VOICES``; ``--voices held-out``: two other voices and speeds that no
setting was tuned on), each with 0.5 s of quiet before and after. Recognition
(``Recognizer.hear``: VAD, grammar and trigram decoders, reconciliation) hears each clip
clean, with noise at ``--snr`` dB, and in babble: ``--babble-talkers`` other espeak-ng
voices (each a different voice, pitch and stream of chatter, none of it a command) talking
at once at ``--babble-snr`` dB, reported as its own condition. The parser turns what was
heard into skill steps.

- **command accuracy**: the heard command gives exactly the skill sequence the text gives;
  a rejected clip counts as a miss, a wrong sequence as a *wrong accept* (the robot would
  do something not asked). Also given for each decoder alone (the grammar's best path, the
  trigram's best hypothesis), to show what reconciling buys.
- **word error rate**: jiwer, over the reconciled text (a rejection is all deletions) and
  over each decoder alone.
- **rejection**: ``--rejection`` clips of white, pink and babble noise, music-like tones
  and off-topic sentences; a clip is rejected when nothing is heard or what is heard
  parses to no skill step, so no skill runs.
- **speed**: CPU seconds of decoding (both decoders, denoising, reconciliation; this
  process's CPU time, so one core) per second of audio, and the largest for commands of
  2.5-3.5 s.

Bad input (a 44.1 kHz stereo WAV, an empty file, a text file, a 10-minute WAV) is checked by
the tests (``tests/speech/test_audio.py``, ``tests/speech/test_recognizer.py``).

The trigram model is trained on 5000 commands generated with seed 0; the spoken commands
use ``--seed`` + 1, and the share of them that also occur verbatim in the training text
is printed.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import numpy as np
from rich.console import Console
from rich.table import Table

from homebot.bench.arguments import add_plot_option, count, seed
from homebot.errors import BenchmarkError, SpeechError
from homebot.progress import track

__all__ = ["add_arguments", "run"]

_SHARED = Path(__file__).resolve().parents[4] / "shared" / "data"
_TRAINING = 5000
_QUIET = 8000  # 0.5 s at 16 kHz

# Sentences a person in a home might say that are not commands to the robot.
OFF_TOPIC = (
    "the weather is nice today isn't it", "my grandmother used to bake apple pie on sundays",
    "please turn the music down a little", "what time does the train to london leave",
    "i think we should paint the walls green", "did you watch the football match yesterday",
    "the cat is sleeping on the windowsill again", "i can't find my reading glasses anywhere",
    "we are going on holiday to spain next month", "this soup needs a bit more salt",
    "the meeting has been moved to thursday afternoon", "how was your day at school",
    "i love the smell of fresh bread in the morning", "the car needs new tyres before winter",
    "she has been learning to play the violin", "let's order pizza for dinner tonight",
    "the garden looks beautiful after the rain", "he forgot to call his mother back",
    "the children are playing in the park", "i have a dentist appointment at three",
    "that film was much better than the book", "our neighbours are having a party",
    "it's going to snow later this week", "could you believe the price of petrol",
    "the baby finally fell asleep", "we need to renew our passports soon",
    "my phone battery is almost empty", "the library closes early on saturdays",
    "i started running every morning", "the flowers on the balcony need water",
    "grandpa tells the same story every christmas", "the printer in the office is broken again",
    "tomorrow is my sister's birthday", "the bus was twenty minutes late",
    "i prefer tea to coffee in the afternoon",
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--count", type=count("--count", 1, 5000), default=300,
                        help="spoken commands per world (default 300)")
    parser.add_argument("--rejection", type=count("--rejection", 0, 5000), default=100,
                        help="noise, tone and off-topic clips to reject (default 100)")
    parser.add_argument("--snr", type=count("--snr", 0, 60), default=10,
                        help="noise level for the noisy pass, in dB SNR (default 10)")
    parser.add_argument("--noise", choices=("white", "babble"), default="white",
                        help="noise of the noisy pass (default white)")
    parser.add_argument("--babble-snr", type=count("--babble-snr", 0, 60), default=10,
                        help="speech over babble, in dB SNR (default 10)")
    parser.add_argument("--babble-talkers", type=count("--babble-talkers", 0, 20), default=6,
                        help="voices talking at once in the babble pass (default 6; 0 skips "
                             "it)")
    parser.add_argument("--robocup", type=Path,
                        default=_SHARED / "robocup" / "CompetitionTemplate",
                        help="RoboCup@Home data directory for the template world (skipped "
                             "when absent)")
    parser.add_argument("--worlds", choices=("both", "apartment", "robocup"), default="both",
                        help="which worlds' commands to speak (default both; one each lets two "
                             "processes share the work)")
    parser.add_argument("--voices", choices=("bench", "held-out"), default="bench",
                        help="the four voices the recogniser was developed with (default), "
                             "or two held-out voices no setting was tuned on")
    parser.add_argument("--seed", type=seed, default=0)
    add_plot_option(parser, "command accuracy by voice, clean and noisy")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Speak, hear and parse; print a table unless ``console`` is None."""
    try:
        from homebot.speech.recognizer import Recognizer
        from homebot.speech.voice import espeak
    except ImportError:  # pragma: no cover - the modules import their extras lazily
        raise BenchmarkError("bench speech needs the speech extra: "
                             "pip install 'homebot[speech]'") from None
    try:
        import jiwer  # noqa: F401
        espeak()
    except (ImportError, SpeechError):
        raise BenchmarkError("bench speech needs the speech extra: "
                             "pip install 'homebot[speech]'") from None
    from homebot.world import World

    apartment_world = World.load("apartment")
    worlds: list[tuple[str, Any]] = []
    if args.worlds in {"both", "apartment"}:
        worlds.append(("apartment", apartment_world))
    notes = []
    if args.worlds == "apartment":
        pass
    elif args.robocup.is_dir():
        from homebot.world.robocup import world_from_robocup

        worlds.append(("robocup_template", World.from_dict(world_from_robocup(args.robocup))))
    else:
        notes.append(f"{args.robocup} absent: RoboCup template world skipped")
    results: dict[str, Any] = {}
    cpu, audio_seconds, three_second = 0.0, 0.0, []
    recognizers = {label: Recognizer.for_world(world, sentences=_TRAINING, seed=0)
                   for label, world in worlds}
    for label, world in worlds:
        figures, timing = _commands(recognizers[label], world, args)
        results[label] = figures
        cpu += timing["cpu"]
        audio_seconds += timing["audio"]
        three_second += timing["three_second"]
    apartment = recognizers.get("apartment") or Recognizer.for_world(
        apartment_world, sentences=_TRAINING, seed=0)
    rejection = _rejection(apartment, apartment_world, args)
    overall = {
        condition: _share(sum(results[label][condition]["correct"] for label in results),
                          sum(results[label][condition]["clips"] for label in results))
        for condition in _conditions(args)}
    figures = {
        "benchmark": "speech",
        "voices": [voice.label() for voice in _voices(args.voices)],
        "noise": f"{args.noise} at {args.snr} dB SNR",
        "babble": (f"{args.babble_talkers} talkers at {args.babble_snr} dB SNR"
                   if args.babble_talkers else None),
        "worlds": results,
        "settings": {"count": args.count, "rejection": args.rejection, "snr": args.snr,
                     "babble_snr": args.babble_snr, "babble_talkers": args.babble_talkers,
                     "seed": args.seed, "worlds": args.worlds, "voice_set": args.voices},
        "command_accuracy": overall,
        "rejection": rejection,
        "speed": {
            "cpu_seconds_per_audio_second": round(cpu / max(audio_seconds, 1e-9), 3),
            "max_cpu_seconds_for_2.5_to_3.5_s_commands":
                round(max(three_second), 3) if three_second else None,
            "commands_2.5_to_3.5_s": len(three_second)},
        "targets": {"clean": 0.90, "noisy": 0.80, "babble": 0.80, "rejected": 0.95,
                    "cpu_seconds_per_audio_second": 0.5},
        "notes": notes,
    }
    if console is not None:
        _print(console, figures)
    if args.plot is not None:
        from homebot.bench.plots import save, speech_figure

        save(speech_figure(results, _conditions(args)), args.plot)
    return figures


def _voices(which: str = "bench") -> tuple[Any, ...]:
    from homebot.speech.voice import HELD_OUT_VOICES, VOICES

    return HELD_OUT_VOICES if which == "held-out" else VOICES


def _conditions(args: argparse.Namespace) -> tuple[str, ...]:
    return ("clean", "noisy", "babble") if args.babble_talkers else ("clean", "noisy")


def _chatter(talkers: int, seed: int) -> list[np.ndarray[Any, Any]]:
    """``talkers`` streams of off-topic talk, each its own voice, pitch and sentences
    (about 15 s each), to be summed into babble."""
    from homebot.speech.voice import VoiceSettings, espeak

    rng = np.random.default_rng(seed)
    names = ("en-us+klatt", "en+klatt2", "en-us+klatt3", "en-us+klatt4", "en+klatt",
             "en-us+klatt2")
    streams = []
    for talker in range(talkers):
        voice = VoiceSettings(names[talker % len(names)], int(rng.integers(120, 170)),
                              int(rng.integers(20, 80)))
        order = rng.permutation(len(OFF_TOPIC))[:5]
        streams.append(espeak().synthesise(". ".join(OFF_TOPIC[i] for i in order), voice))
    return streams


def _share(part: int, whole: int) -> float | None:
    return round(part / whole, 4) if whole else None


def _padded(speech: np.ndarray[Any, Any]) -> np.ndarray[Any, Any]:
    quiet = np.zeros(_QUIET, dtype=np.int16)
    return np.concatenate([quiet, speech, quiet])


def _commands(recognizer: Any, world: Any, args: argparse.Namespace
              ) -> tuple[dict[str, Any], dict[str, Any]]:
    """Accuracy, WER and timing of ``args.count`` spoken commands, clean and noisy."""
    import jiwer

    from homebot.language import Vocabulary, parse_command
    from homebot.language.generator import generate_commands
    from homebot.speech.audio import add_noise, babble
    from homebot.speech.grammar import words_of
    from homebot.speech.voice import espeak

    vocabulary = Vocabulary.from_world(world)
    training = {words_of(text) for text, _ in generate_commands(world, _TRAINING, 0)}
    commands = generate_commands(world, args.count, args.seed + 1)
    rng = np.random.default_rng(args.seed)
    voices = _voices(args.voices)
    babblers = [espeak().synthesise(text, voices[index % len(voices)])
                for index, (text, _) in enumerate(generate_commands(world, 6, args.seed + 2))]
    talkers = _chatter(args.babble_talkers, args.seed + 5)

    def steps_of(text: str | None) -> list[Any] | None:
        if not text:
            return None
        parsed = parse_command(text, vocabulary)
        return list(parsed.steps) if parsed else None

    tallies: dict[str, Any] = {}
    cpu = audio = 0.0
    three_second: list[float] = []
    for condition in _conditions(args):
        tally = {"clips": 0, "correct": 0, "rejected": 0, "wrong_accepts": 0,
                 "grammar_only_correct": 0, "ngram_only_correct": 0}
        by_voice: dict[str, dict[str, int]] = {}
        references: list[str] = []
        heard: list[str] = []
        grammar_heard: list[str] = []
        ngram_heard: list[str] = []
        reasons: dict[str, int] = {}
        for index, (text, _) in enumerate(track(commands, f"spoken commands, {condition}")):
            voice = voices[index % len(voices)]
            speech = espeak().synthesise(text, voice)
            clip = _padded(speech)
            if condition == "noisy":
                noise = (rng.standard_normal(clip.size) if args.noise == "white"
                         else babble(babblers, clip.size, rng))
                clip = add_noise(clip, noise, args.snr)
            elif condition == "babble":
                clip = add_noise(clip, babble(talkers, clip.size, rng), args.babble_snr)
            hearing = recognizer.hear(clip)
            cpu += hearing.decode_seconds
            audio += hearing.seconds
            if condition == "clean" and 2.5 <= speech.size / 16_000 <= 3.5:
                three_second.append(hearing.decode_seconds)
            expected = steps_of(text)
            got = steps_of(hearing.text)
            tally["clips"] += 1
            spoken = by_voice.setdefault(voice.label(), {"clips": 0, "correct": 0})
            spoken["clips"] += 1
            spoken["correct"] += hearing.text is not None and got == expected
            reasons[hearing.reason] = reasons.get(hearing.reason, 0) + 1
            if hearing.text is None:
                tally["rejected"] += 1
            elif got == expected:
                tally["correct"] += 1
            else:
                tally["wrong_accepts"] += 1
            top = hearing.ngram_hypotheses[0] if hearing.ngram_hypotheses else ""
            tally["grammar_only_correct"] += steps_of(hearing.grammar_hypothesis) == expected
            tally["ngram_only_correct"] += steps_of(top) == expected
            references.append(words_of(text))
            heard.append(hearing.text or "")
            grammar_heard.append(hearing.grammar_hypothesis or "")
            ngram_heard.append(top)
        tallies[condition] = {
            **tally,
            "accuracy": _share(tally["correct"], tally["clips"]),
            "grammar_only_accuracy": _share(tally["grammar_only_correct"], tally["clips"]),
            "ngram_only_accuracy": _share(tally["ngram_only_correct"], tally["clips"]),
            "wer": round(float(jiwer.wer(references, heard)), 4),
            "grammar_only_wer": round(float(jiwer.wer(references, grammar_heard)), 4),
            "ngram_only_wer": round(float(jiwer.wer(references, ngram_heard)), 4),
            "reasons": dict(sorted(reasons.items())),
            "by_voice": by_voice,
        }
    overlap = sum(words_of(text) in training for text, _ in commands)
    timing = {"cpu": cpu, "audio": audio, "three_second": three_second}
    return {**tallies, "commands_also_in_training_text": overlap}, timing


def _rejection(recognizer: Any, world: Any, args: argparse.Namespace) -> dict[str, Any]:
    """Noise, tones and off-topic speech: how many are rejected (no skill would run)."""
    from homebot.language import Vocabulary, parse_command
    from homebot.language.generator import generate_commands
    from homebot.speech.audio import babble, tones
    from homebot.speech.voice import espeak

    vocabulary = Vocabulary.from_world(world)
    rng = np.random.default_rng(args.seed + 3)
    voices = _voices(args.voices)
    babblers = [espeak().synthesise(text, voices[index % len(voices)])
                for index, (text, _) in enumerate(generate_commands(world, 6, args.seed + 4))]
    kinds = ("white noise", "pink noise", "babble", "tones", "off-topic", "off-topic")
    counts: dict[str, list[int]] = {kind: [0, 0] for kind in kinds}
    accepted_texts = []
    for index in track(range(args.rejection), "rejection clips"):
        kind = kinds[index % len(kinds)]
        seconds = float(rng.uniform(2.0, 5.0))
        length = int(seconds * 16_000)
        if kind == "white noise":
            clip = (rng.standard_normal(length) * 3000).astype(np.int16)
        elif kind == "pink noise":
            spectrum = np.fft.rfft(rng.standard_normal(length))
            spectrum /= np.sqrt(np.arange(1, spectrum.size + 1))
            pink = np.fft.irfft(spectrum, length)
            clip = (pink / np.max(np.abs(pink)) * 12000).astype(np.int16)
        elif kind == "babble":
            mixed = babble(babblers, length, rng)
            clip = (mixed / max(1.0, float(np.max(np.abs(mixed)))) * 20000).astype(np.int16)
        elif kind == "tones":
            clip = tones(seconds, rng)
        else:
            sentence = OFF_TOPIC[(index // len(kinds) * 2 + index % 2) % len(OFF_TOPIC)]
            clip = _padded(espeak().synthesise(sentence, voices[index % len(voices)]))
        hearing = recognizer.hear(clip)
        runs = bool(hearing.text) and bool(parse_command(hearing.text, vocabulary))
        counts[kind][0] += 1
        counts[kind][1] += not runs
        if runs:
            accepted_texts.append(f"{kind}: {hearing.text}")
    clips = sum(total for total, _ in counts.values())
    rejected = sum(kept for _, kept in counts.values())
    return {"clips": clips, "rejected": rejected, "share": _share(rejected, clips),
            "by_kind": {kind: {"clips": total, "rejected": kept}
                        for kind, (total, kept) in counts.items()},
            "accepted": accepted_texts}


def _print(console: Console, figures: dict[str, Any]) -> None:
    table = Table(title=f"speech: voices {', '.join(figures['voices'])}; noisy = "
                        f"{figures['noise']}")
    for column in ("world", "condition", "clips", "accuracy", "grammar only", "trigram only",
                   "rejected", "wrong", "WER", "WER grammar", "WER trigram"):
        table.add_column(column)
    for world, conditions in figures["worlds"].items():
        for condition in ("clean", "noisy", "babble"):
            if condition not in conditions:
                continue
            row = conditions[condition]
            table.add_row(world, condition, str(row["clips"]), f"{row['accuracy']:.1%}",
                          f"{row['grammar_only_accuracy']:.1%}",
                          f"{row['ngram_only_accuracy']:.1%}", str(row["rejected"]),
                          str(row["wrong_accepts"]), f"{row['wer']:.3f}",
                          f"{row['grammar_only_wer']:.3f}", f"{row['ngram_only_wer']:.3f}")
    console.print(table)
    accuracy = figures["command_accuracy"]
    if accuracy["clean"] is not None:
        console.print(f"command accuracy: clean {accuracy['clean']:.1%} (target 90 %), noisy "
                      f"{accuracy['noisy']:.1%} (target 80 %)" + (
                          f", babble {accuracy['babble']:.1%} ({figures['babble']})"
                          if "babble" in accuracy else ""))
    rejection = figures["rejection"]
    if rejection["clips"]:
        console.print(f"rejected {rejection['rejected']}/{rejection['clips']} "
                      f"({rejection['share']:.1%}, target 95 %): " + ", ".join(
                          f"{kind} {row['rejected']}/{row['clips']}"
                          for kind, row in rejection["by_kind"].items()))
    speed = figures["speed"]
    console.print(f"speed: {speed['cpu_seconds_per_audio_second']} CPU s per audio s "
                  f"(target 0.5); largest for 2.5-3.5 s commands: "
                  f"{speed['max_cpu_seconds_for_2.5_to_3.5_s_commands']} s "
                  f"over {speed['commands_2.5_to_3.5_s']} (target 1.5 s)")
    for note in figures["notes"]:
        console.print(f"note: {note}")
