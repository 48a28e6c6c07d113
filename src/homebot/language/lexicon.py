"""The fixed words of GPSR commands: verbs, people, gestures, clothes, topics, fillers.

Everything here is world-independent and immutable (tuples and frozensets); the
world's own names come from ``homebot.language.vocabulary``. Phrases are written
as they look after normalisation: lower case, no punctuation, hyphens as spaces.
"""

from __future__ import annotations

__all__ = [
    "ACTIONS",
    "ARTICLES",
    "CATEGORY_PHRASES",
    "CLOTHING_COLOURS",
    "CLOTHING_GARMENTS",
    "COMMON_WORDS",
    "CONTRACTIONS",
    "FILLERS",
    "FUNCTION_WORDS",
    "GENERIC_OBJECT_WORDS",
    "GESTURES",
    "IMPOSSIBLE_ACTIONS",
    "INFO_WORDS",
    "NEGATIONS",
    "PERSON_NOUNS",
    "POSSESSIVES",
    "POSTURES",
    "PREPOSITIONS",
    "PROPERTIES",
    "QUANTITIES",
    "SEPARATORS",
    "TOPICS",
    "WEARING_MARKERS",
]

# Verb phrases and the action they name. "take" is resolved to guide when its
# object is a person; "bring" likewise.
ACTIONS: tuple[tuple[str, str], ...] = (
    ("go", "go"), ("navigate", "go"), ("move", "go"), ("head", "go"), ("drive", "go"),
    ("walk", "go"), ("proceed", "go"), ("travel", "go"), ("make your way", "go"),
    ("come", "go"), ("return", "return"), ("go back", "return"), ("come back", "return"),
    ("head back", "return"), ("get back", "return"),
    ("find", "find"), ("locate", "find"), ("look for", "find"), ("search for", "find"),
    ("seek", "find"), ("spot", "find"), ("track down", "find"), ("look around for", "find"),
    ("search", "find"), ("try to find", "find"), ("identify", "find"),
    ("meet", "meet"), ("get to know", "meet"),
    ("take", "take"), ("get", "take"), ("grasp", "take"), ("fetch", "take"), ("grab", "take"),
    ("pick up", "take"), ("pick", "take"), ("collect", "take"), ("retrieve", "take"),
    ("obtain", "take"),
    ("bring", "bring"), ("give", "bring"), ("deliver", "bring"), ("hand", "bring"),
    ("hand over", "bring"), ("pass", "bring"), ("serve", "bring"), ("carry", "bring"),
    ("put", "place"), ("place", "place"), ("leave", "place"), ("set", "place"),
    ("drop", "place"), ("deposit", "place"), ("store", "place"), ("put down", "place"),
    ("set down", "place"), ("lay", "place"), ("drop off", "place"),
    ("count", "count"),
    ("tell", "tell"), ("say", "tell"), ("speak", "tell"), ("report", "tell"),
    ("inform", "tell"), ("remind", "tell"), ("let", "tell"), ("let me know", "tell_me"),
    ("let us know", "tell_me"),
    ("announce", "tell"), ("state", "tell"), ("find out", "tell_me"),
    ("answer", "answer"), ("respond to", "answer"), ("reply to", "answer"),
    ("greet", "greet"), ("salute", "greet"), ("say hello to", "greet"), ("say hi to", "greet"),
    ("introduce yourself to", "greet"), ("welcome", "greet"), ("wave to", "greet"),
    ("follow", "follow"), ("go after", "follow"), ("walk behind", "follow"),
    ("guide", "guide"), ("escort", "guide"), ("lead", "guide"), ("accompany", "guide"),
    ("show the way", "guide"), ("walk with", "guide"),
    ("ask", "ask"), ("look at", "look"), ("inspect", "look"), ("open", "open"),
    ("i want", "want"), ("i would like", "want"), ("i need", "want"), ("i wish", "want"),
    ("can i have", "want"), ("could i have", "want"), ("can i get", "want"),
    ("could i get", "want"), ("i would love", "want"), ("may i have", "want"),
    ("would like", "want"), ("wants", "want"), ("needs", "want"), ("would love", "want"),
    ("introduce yourself", "greet"), ("say hello", "greet"), ("say hi", "greet"),
    ("describe", "describe_person"),
    ("what is in", "contents"), ("what is on", "contents"), ("what is inside", "contents"),
    ("what is there", "contents"), ("what do we have in", "contents"),
    ("what do we have on", "contents"), ("what is there in", "contents"),
    ("what is there on", "contents"), ("what is inside of", "contents"),
    ("what is on top of", "contents"), ("what do you see on", "contents"),
    ("what do you see in", "contents"), ("what is lying on", "contents"),
    ("where is", "where"), ("where are", "where"), ("do you know where", "where"),
    ("where did i leave", "where"), ("where did i put", "where"),
    ("where have i left", "where"), ("where have i put", "where"),
    ("tell me where", "where"), ("let me know where", "where"), ("show", "guide"),
    ("come with me", "follow"), ("pop", "go"), ("pop into", "go"), ("pop over to", "go"),
    ("would be great", "want"), ("would be nice", "want"), ("would be lovely", "want"),
    ("search", "search"), ("look around", "search"), ("have a look around", "search"),
    ("have a look in", "search"), ("check", "search"),
)

# Words for how many things: "two drinks", "a couple of snacks", "all the fruits".
QUANTITIES: tuple[tuple[str, int | str], ...] = (
    ("two", 2), ("three", 3), ("four", 4), ("five", 5), ("six", 6), ("2", 2), ("3", 3),
    ("4", 4), ("5", 5), ("6", 6), ("a couple of", 2), ("a pair of", 2), ("both", 2),
    ("all", "all"), ("all the", "all"), ("all of the", "all"), ("every", "all"),
    ("each", "all"), ("a few", "all"), ("several", "all"),
)

# Actions people ask for that no skill can do; a refusal names them.
IMPOSSIBLE_ACTIONS: frozenset[str] = frozenset({
    "cook", "clean", "wash", "fly", "sing", "dance", "call", "phone", "eat",
    "swim", "paint", "write", "read", "repair", "fix", "build", "buy", "cut", "throw",
    "break", "kick", "destroy", "iron", "sweep", "vacuum", "mop", "close", "lock",
    "unlock", "turn", "switch", "sleep", "jump", "kill", "hit", "make", "feed", "fold",
    "warm", "heat", "boil", "fry", "bake", "stir", "pour", "fill", "empty", "light", "hug",
    "kiss", "record", "film", "order", "print", "charge", "shake", "scrub", "tidy", "water",
    "help", "wake", "massage", "do", "play", "sort", "hang", "cover", "wipe", "dry",
    "chop", "peel", "slice", "mix", "blend", "watch", "drink",
})

# Everyday words that are never taken for a misspelt name ("weather" is not "sweater").
COMMON_WORDS: frozenset[str] = frozenset({
    "weather", "forecast", "news", "music", "song", "dinner", "lunch", "breakfast",
    "ready", "home", "later", "soon", "tonight", "tomorrow", "morning", "evening", "night",
    "minutes", "hours", "mother", "father", "brother", "sister", "children", "kids",
    "newspaper", "book", "keys", "phone", "wallet", "glasses", "money", "homework",
    "garden", "garage", "balcony", "attic", "basement", "porch", "street", "car", "cars",
    "dog", "cat", "plants", "flowers", "lights", "window", "windowsill", "drawer",
    "microwave", "oven", "stove", "sink", "towel", "knife", "board", "blender",
    "please", "thanks", "really", "maybe", "quietly", "gently", "spilling", "cold",
    "hot", "clean", "dirty", "favourite", "favorite", "would", "like", "want", "wants",
    "served", "starting", "started", "leaving", "arrived", "waiting", "coming",
    "called", "calling", "asleep", "awake", "outside", "upstairs", "downstairs",
})

# Words that turn a command round ("not the lemonade", "unless Maria wants it"): the
# parser cannot honour them, so a command with one is asked about, never carried out.
NEGATIONS: frozenset[str] = frozenset({"not", "unless", "except", "without", "never",
                                       "neither", "nor", "instead"})

# Phrases that join clauses; normalisation turns them into the "then" separator.
SEPARATORS: tuple[str, ...] = (
    "then", "and then", "and", "after that", "afterwards", "afterward", "next",
    "and after that", "once done", "once you are done", "when you are done", "finally",
    "once there", "when you are there", "once you are there", "and finally", "also",
    "and also", "later", "subsequently", "after which",
)

# Politeness and filler, removed before parsing.
FILLERS: tuple[str, ...] = (
    "could you please", "can you please", "would you please", "will you please",
    "could you", "can you", "would you", "will you", "would you mind", "would you kindly",
    "please", "kindly", "i want you to", "i would like you to", "i need you to",
    "i would like to ask you to", "i am asking you to", "i would appreciate it if you",
    "i would appreciate it if you could", "be so kind as to", "be a dear and",
    "go ahead and", "if you can", "if possible", "if you could", "thanks", "thank you",
    "thank you very much", "okay", "ok", "hey", "hello robot", "hi robot", "robot",
    "homebot", "hey robot", "dear robot", "now", "quickly", "right away",
    "immediately", "as soon as possible", "asap", "first", "firstly", "first of all",
    "to start", "start by", "begin by", "start with", "would you be so kind as to",
    "be so kind and", "i would appreciate it if you could", "when you get a chance",
    "your task is to", "you need to", "you should", "you must", "try and", "just",
    "carefully", "there", "over", "over there", "right now", "real quick", "buddy",
    "pal", "mate", "the robot", "for us", "i wonder if you could", "do me a favour and",
    "do me a favor and", "nicely", "politely", "please do", "like", "um", "uh", "erm",
    "well", "actually", "you know", "i mean", "i am thirsty", "i am hungry", "i am bored",
    "wait there", "and wait there", "wait for me there", "and wait", "go and", "come on",
    "glass of", "bottle of", "can of", "bag of", "bowl of", "cup of", "box of", "packet of",
    "carton of", "jar of", "tin of", "slice of", "piece of", "pack of", "mug of",
)

CONTRACTIONS: tuple[tuple[str, str], ...] = (
    ("what's", "what is"), ("who's", "who is"), ("that's", "that is"),
    ("it's", "it is"), ("there's", "there is"), ("there're", "there are"),
    ("i'd", "i would"), ("you'd", "you would"), ("i'm", "i am"), ("you're", "you are"),
    ("they're", "they are"), ("let's", "let us"), ("don't", "do not"),
    ("can't", "cannot"), ("won't", "will not"), ("i've", "i have"), ("you've", "you have"),
    ("he's", "he is"), ("she's", "she is"), ("where's", "where is"),
    ("how's", "how is"), ("isn't", "is not"), ("aren't", "are not"),
    ("he'd", "he would"), ("she'd", "she would"), ("they'd", "they would"),
    ("we'd", "we would"), ("we're", "we are"), ("we've", "we have"), ("he'll", "he will"),
    ("she'll", "she will"), ("they'll", "they will"), ("we'll", "we will"),
    ("i'll", "i will"), ("you'll", "you will"),
)

PERSON_NOUNS: frozenset[str] = frozenset({
    "person", "persons", "people", "someone", "somebody", "anyone", "anybody", "guy",
    "guys", "man", "men", "woman", "women", "lady", "ladies", "gentleman", "individual",
    "individuals", "human", "humans", "visitor", "guest", "guests", "folks", "everyone",
    "everybody", "whoever",
})

# Posture words and phrases (before or after a person noun) -> Posture value.
POSTURES: tuple[tuple[str, str], ...] = (
    ("sitting", "sitting"), ("seated", "sitting"), ("sitting down", "sitting"),
    ("sat", "sitting"), ("standing", "standing"), ("standing up", "standing"),
    ("lying", "lying"), ("lying down", "lying"), ("laying", "lying"),
    ("laying down", "lying"), ("lying on the floor", "lying"),
)

# "their" in these phrases stands for any of POSSESSIVES (his, her, the...).
POSSESSIVES: tuple[str, ...] = ("their", "his", "her", "the", "an", "one")

GESTURES: tuple[tuple[str, str], ...] = (
    ("waving", "waving"), ("waving their hand", "waving"), ("waving their hands", "waving"),
    ("waving at me", "waving"), ("who waves", "waving"), ("waving their arm", "waving"),
    ("raising their left arm", "raising_left_arm"),
    ("raising left arm", "raising_left_arm"),
    ("with their left arm raised", "raising_left_arm"),
    ("with their left arm up", "raising_left_arm"),
    ("holding up their left arm", "raising_left_arm"),
    ("lifting their left arm", "raising_left_arm"),
    ("raising their left hand", "raising_left_arm"),
    ("with their left hand raised", "raising_left_arm"),
    ("raising their right arm", "raising_right_arm"),
    ("raising right arm", "raising_right_arm"),
    ("with their right arm raised", "raising_right_arm"),
    ("with their right arm up", "raising_right_arm"),
    ("holding up their right arm", "raising_right_arm"),
    ("lifting their right arm", "raising_right_arm"),
    ("raising their right hand", "raising_right_arm"),
    ("with their right hand raised", "raising_right_arm"),
    ("pointing to the left", "pointing_left"), ("pointing left", "pointing_left"),
    ("pointing to their left", "pointing_left"), ("pointing towards the left", "pointing_left"),
    ("pointing toward the left", "pointing_left"), ("pointing at the left", "pointing_left"),
    ("pointing leftwards", "pointing_left"), ("pointing left side", "pointing_left"),
    ("pointing to the right", "pointing_right"), ("pointing right", "pointing_right"),
    ("pointing to their right", "pointing_right"),
    ("pointing towards the right", "pointing_right"),
    ("pointing toward the right", "pointing_right"),
    ("pointing at the right", "pointing_right"), ("pointing rightwards", "pointing_right"),
)

# Colour words and their canonical spelling; garments (singular, plural forms).
CLOTHING_COLOURS: tuple[tuple[str, str], ...] = (
    ("blue", "blue"), ("yellow", "yellow"), ("black", "black"), ("white", "white"),
    ("red", "red"), ("orange", "orange"), ("gray", "gray"), ("grey", "gray"),
    ("green", "green"), ("pink", "pink"), ("purple", "purple"), ("brown", "brown"),
    ("dark blue", "dark blue"), ("light blue", "light blue"), ("beige", "beige"),
)
CLOTHING_GARMENTS: tuple[tuple[str, str], ...] = (
    ("t shirt", "t-shirt"), ("t shirts", "t-shirt"), ("tshirt", "t-shirt"),
    ("tshirts", "t-shirt"), ("tee", "t-shirt"), ("shirt", "shirt"), ("shirts", "shirt"),
    ("blouse", "blouse"), ("blouses", "blouse"), ("sweater", "sweater"),
    ("sweaters", "sweater"), ("jumper", "sweater"), ("jumpers", "sweater"),
    ("pullover", "sweater"), ("hoodie", "sweater"), ("coat", "coat"), ("coats", "coat"),
    ("jacket", "jacket"), ("jackets", "jacket"), ("dress", "dress"), ("dresses", "dress"),
    ("trousers", "trousers"), ("pants", "trousers"), ("jeans", "jeans"), ("skirt", "skirt"),
    ("skirts", "skirt"), ("cap", "cap"), ("caps", "cap"), ("hat", "hat"), ("hats", "hat"),
)
WEARING_MARKERS: tuple[str, ...] = (
    "wearing", "who is wearing", "that is wearing", "who are wearing", "that are wearing",
    "dressed in", "who wears", "who has", "who have", "that wears", "clad in",
    "who is dressed in", "that is dressed in", "are wearing", "is wearing", "wear",
    "who wear", "having",
)

# Prepositions (and phrases acting as one) -> the preposition they amount to.
PREPOSITIONS: tuple[tuple[str, str], ...] = (
    ("to", "to"), ("into", "to"), ("towards", "to"), ("toward", "to"), ("over to", "to"),
    ("up to", "to"), ("back to", "to"), ("down to", "to"), ("on", "on"), ("onto", "on"),
    ("on top of", "on"), ("upon", "on"), ("located on", "on"), ("placed on", "on"),
    ("in", "in"), ("inside", "in"), ("inside of", "in"), ("within", "in"),
    ("located in", "in"), ("at", "at"), ("located at", "at"), ("near", "at"),
    ("next to", "at"), ("close to", "at"), ("beside", "at"), ("by", "at"),
    ("in front of", "at"), ("from", "from"), ("out of", "from"), ("off", "from"),
    ("off of", "from"), ("of", "of"), ("for", "for"), ("with", "with"),
)
ARTICLES: frozenset[str] = frozenset({"the", "a", "an", "some", "any", "this", "that", "one"})

# Talk topics -> the canonical phrase passed as say(info=...).
TOPICS: tuple[tuple[str, str], ...] = (
    ("the time", "the time"), ("what time it is", "the time"), ("what time is it", "the time"),
    ("the current time", "the time"), ("the hour", "the time"),
    ("what day is today", "what day is today"), ("what day it is today", "what day is today"),
    ("what day it is", "what day is today"), ("what day is it today", "what day is today"),
    ("what day is it", "what day is today"), ("what is the time", "the time"),
    ("what is the date", "what day is today"), ("what is the date today", "what day is today"),
    ("today s date", "what day is today"),
    ("todays date", "what day is today"), ("the date", "what day is today"),
    ("the date today", "what day is today"), ("which day it is today", "what day is today"),
    ("which day is today", "what day is today"), ("what today is", "what day is today"),
    ("what day is tomorrow", "what day is tomorrow"),
    ("what day it is tomorrow", "what day is tomorrow"),
    ("what day it will be tomorrow", "what day is tomorrow"),
    ("tomorrows date", "what day is tomorrow"), ("which day is tomorrow", "what day is tomorrow"),
    ("what tomorrow is", "what day is tomorrow"),
    ("the day of the week", "the day of the week"),
    ("what day of the week it is", "the day of the week"),
    ("which day of the week it is", "the day of the week"),
    ("the weekday", "the day of the week"), ("the current weekday", "the day of the week"),
    ("the day of the month", "the day of the month"),
    ("what day of the month it is", "the day of the month"),
    ("which day of the month it is", "the day of the month"),
    ("something about yourself", "something about yourself"),
    ("something about you", "something about yourself"),
    ("a little about yourself", "something about yourself"),
    ("about yourself", "something about yourself"), ("who you are", "something about yourself"),
    ("your teams name", "your team's name"), ("your team name", "your team's name"),
    ("the name of your team", "your team's name"), ("the team name", "your team's name"),
    ("your teams country", "your team's country"), ("your team country", "your team's country"),
    ("the country of your team", "your team's country"),
    ("where your team is from", "your team's country"),
    ("which country your team is from", "your team's country"),
    ("what country your team is from", "your team's country"),
    ("your teams affiliation", "your team's affiliation"),
    ("your team affiliation", "your team's affiliation"),
    ("the affiliation of your team", "your team's affiliation"),
    ("your affiliation", "your team's affiliation"),
    ("a joke", "a joke"), ("a funny joke", "a joke"), ("a story", "a story"),
)

# What describe(info=...) can tell about a person.
INFO_WORDS: tuple[tuple[str, str], ...] = (
    ("name", "name"), ("pose", "pose"), ("posture", "pose"), ("gesture", "gesture"),
    ("clothes", "clothes"), ("outfit", "clothes"), ("clothing", "clothes"),
    ("what they are wearing", "clothes"), ("what she is wearing", "clothes"),
    ("what he is wearing", "clothes"), ("what they wear", "clothes"),
)

# Superlatives for describe(property=...).
PROPERTIES: tuple[tuple[str, str], ...] = (
    ("biggest", "biggest"), ("largest", "biggest"), ("smallest", "smallest"),
    ("tiniest", "smallest"), ("heaviest", "heaviest"), ("lightest", "lightest"),
    ("thinnest", "thinnest"), ("slimmest", "thinnest"), ("thickest", "thickest"),
    ("widest", "biggest"),
)

GENERIC_OBJECT_WORDS: frozenset[str] = frozenset({
    "object", "objects", "item", "items", "thing", "things", "stuff",
})

# Paraphrases of a category ("something to drink"): phrase -> candidate categories.
CATEGORY_PHRASES: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("something to drink", ("drink",)), ("anything to drink", ("drink",)),
    ("a beverage", ("drink",)), ("beverage", ("drink",)), ("beverages", ("drink",)),
    ("something to eat", ("food", "snack", "fruit")),
    ("anything to eat", ("food", "snack", "fruit")),
    ("something to play with", ("toy",)), ("something to clean with", ("cleaning supply",)),
    ("a piece of fruit", ("fruit",)), ("some fruit", ("fruit",)), ("soda", ("drink",)),
    ("a soda", ("drink",)), ("a cold one", ("drink",)), ("a cold drink", ("drink",)),
    ("sodas", ("drink",)), ("something to nibble", ("snack",)), ("a treat", ("snack",)),
)

# Words that are never misspellings of a name (the fuzzy matcher leaves them alone).
_FUNCTION_WORDS_TEXT = """
a an the this that these those it its them they their his her him he she me my
mine i you your yours we us our to from in on at into onto inside of off by with
near next beside for up down out over under behind above below around then and or
but so if is are was were be been being am do does did have has had there here
what which who whom whose where when how many much some any all each every one two
three four five six seven eight nine ten no not yes can could would should will
shall may might must let lets as than too very also just only please tell say
there's top left right side arm arms hand hands towards toward way back again
other another same whatever anything something somebody nothing own is where located
currently standing sitting lying waving pointing raising wearing dressed located
placed lies sits stands find then today tomorrow week month day time date
question questions quiz quizzes riddle ones room know
"""
FUNCTION_WORDS: frozenset[str] = frozenset(_FUNCTION_WORDS_TEXT.split())
