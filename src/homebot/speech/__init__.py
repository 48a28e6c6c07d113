"""Speech in and out: recognition with pocketsphinx, the robot's voice with espeak-ng.

Needs the ``speech`` extra (``pip install 'homebot[speech]'``); importing this package
does not, only building a ``Recognizer`` or a ``Voice`` does.
"""

from homebot.speech.audio import SAMPLE_RATE, read_wav, write_wav
from homebot.speech.grammar import Grammar, command_grammar, drink_grammar, yes_no_grammar
from homebot.speech.recognizer import DIALOGUE_STATES, Hearing, Recognizer, state_for_question
from homebot.speech.segmentation import Segmenter, Utterance
from homebot.speech.voice import VOICES, Voice, VoiceSettings, espeak

__all__ = [
    "DIALOGUE_STATES",
    "SAMPLE_RATE",
    "VOICES",
    "Grammar",
    "Hearing",
    "Recognizer",
    "Segmenter",
    "Utterance",
    "Voice",
    "VoiceSettings",
    "command_grammar",
    "drink_grammar",
    "espeak",
    "read_wav",
    "state_for_question",
    "write_wav",
    "yes_no_grammar",
]
