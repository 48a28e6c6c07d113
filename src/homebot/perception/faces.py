"""Faces: a boosted Haar-feature cascade finds them, random forests tell whose they are.

CAESAR §2.4 and Cosero §7.1.2. Both steps read Haar-like features: sums of
rectangles of the image, each taken in four look-ups of the integral image
(Viola and Jones), normalised by the window's area and contrast so that light
level does not matter.

- **Detection** (``FaceDetector``): windows slide over the image at several
  sizes; a cascade of two AdaBoost stages of decision stumps (scikit-learn)
  rejects most windows with a few features and scores the rest with more; the
  best-scoring windows, overlaps merged, are faces. OpenCV's shipped cascade
  would be the first choice, but the OpenCV in use (5.x) no longer has
  ``CascadeClassifier`` nor ships the cascade files, so the cascade is trained
  here, on example faces and faceless images the caller gives.
- **Alignment**: the best-scoring window is often a few pixels off the face
  (median overlap 0.82 with the true one); a regression forest on the cascade's
  features, trained on shifted and resized windows of the training faces, moves
  it onto the face (twice), and a second, finer forest, trained on where the first
  leaves windows (cascaded regression), once more. Identifying with the true windows
  would find 98 % of a seed's faces against 94 % with the raw ones.
- **Identification** (``FaceMemory``): a random forest on a larger bank of Haar
  features of the face window votes for an identity; each enrolled view is also
  learnt mirrored. ``enrol(name, images)`` adds a person online (the forest is grown
  again on everything enrolled: seconds). The identification features are divided by
  the contrast of the window's middle (its corners show the background). Strangers are rejected by
  distance: a face further from the voted person's enrolled views than
  ``threshold`` times their reach (in the forest's 800 most telling features,
  each standardised and weighed by the square root of its importance) is nobody
  known; a person's reach is learnt from their enrolment images alone, each held
  out in turn (``_held_out_distances``): the median of those distances times the
  household's 95th percentile of them over their person's median, then shrunk halfway
  towards the household's median reach. Faces of people nobody knows
  (``enrol_strangers``: the faces the cascade was trained on, say) are one more class
  of the forest: a face voted a stranger's is nobody known however near someone it
  lies. With them the reach can be wider (each person's own 90th percentile before):
  the class takes many strangers a wider reach would let in. The forest's own vote
  share and leaf proximity, and a per-person spread model, separated strangers worse.
- **A look** (``identify_look``, ``identify_views``): several views of one person
  are weighed together, not by a majority of per-view decisions: the votes summed
  over the views pick the person, and the median of the views' distances from
  them must be within a threshold learnt from looks drawn from held-out enrolment
  images. A stranger's look is named far less often than a stranger's view.
- **Online enrolment** (``Acquaintances``, ``introduced_name``): "my name is ..."
  said in front of the robot enrols the views of the face in front under that name.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from homebot.errors import HomebotError

__all__ = ["Acquaintances", "FaceDetector", "FaceError", "FaceMemory", "FaceWindow",
           "HaarFeatures", "integral_image", "introduced_name"]

Window = tuple[int, int, int]  #: x, y, side in pixels
_TELLING = 800  #: features the forest rates highest, for the distance to a person's views
_NEAREST = 3  #: enrolled views a face is compared with
#: quantile of held-out enrolment distances (each over their person's median): the reach
_HELD_OUT = 0.95
#: how much of a person's own reach is kept: it is shrunk (geometrically) halfway towards
#: the household's median reach (a face whose views vary much, such as a low-contrast one,
#: otherwise reached so far that it took in most strangers' faces)
_OWN_REACH = 0.5
#: the enrolled windows around each aligned one: x, y, side in pixels (the first is the
#: window itself)
_SHIFTS = ((0, 0, 0), (-1, 0, 0), (1, 0, 0), (0, -1, 0), (0, 1, 0), (-1, -1, 2), (1, 1, -2))
_LOOK_QUANTILE = 0.9  #: of the held-out enrolment looks' distances: a look's threshold
_LOOK_DRAWS = 200  #: held-out enrolment looks drawn per person for that threshold


class FaceError(HomebotError):
    """Faces used wrongly: identifying before anyone is enrolled, an empty enrolment."""


def integral_image(image: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The integral image of ``image`` and of its square, each padded with a zero row and
    column: the sum over rows r0:r1, columns c0:c1 is I[r1,c1] - I[r0,c1] - I[r1,c0] + I[r0,c0]."""
    values = np.asarray(image, dtype=np.float64)
    padded = np.zeros((values.shape[0] + 1, values.shape[1] + 1))
    squares = np.zeros_like(padded)
    padded[1:, 1:] = values.cumsum(0).cumsum(1)
    squares[1:, 1:] = (values ** 2).cumsum(0).cumsum(1)
    return padded, squares


class HaarFeatures:
    """A seeded bank of Haar-like features on the unit window: two-, three- and
    four-rectangle patterns, horizontal and vertical, at random places and sizes.

    Args:
        count: how many features.
        seed: the bank's layout.
    """

    def __init__(self, count: int, seed: int = 0, inset: float = 0.0) -> None:
        rng = np.random.default_rng([seed, 2004])
        rects: list[tuple[float, float, float, float, float]] = []
        owners: list[int] = []
        for feature in range(count):
            kind = int(rng.integers(0, 5))
            span = 1.0 - 2 * inset
            w, h = rng.uniform(0.1, 0.8, 2) * span
            x, y = inset + rng.uniform(0.0, span - w), inset + rng.uniform(0.0, span - h)
            parts: list[tuple[float, float, float, float, float]]
            if kind == 0:  # left | right
                parts = [(x, y, x + w / 2, y + h, 1.0), (x + w / 2, y, x + w, y + h, -1.0)]
            elif kind == 1:  # top / bottom
                parts = [(x, y, x + w, y + h / 2, 1.0), (x, y + h / 2, x + w, y + h, -1.0)]
            elif kind == 2:  # three across: the middle against both sides
                parts = [(x, y, x + w, y + h, 1.0), (x + w / 3, y, x + 2 * w / 3, y + h, -3.0)]
            elif kind == 3:  # three down
                parts = [(x, y, x + w, y + h, 1.0), (x, y + h / 3, x + w, y + 2 * h / 3, -3.0)]
            else:  # four: a chequer
                parts = [(x, y, x + w, y + h, 1.0), (x + w / 2, y, x + w, y + h / 2, -2.0),
                         (x, y + h / 2, x + w / 2, y + h, -2.0)]
            rects.extend(parts)
            owners.extend([feature] * len(parts))
        table = np.asarray(rects)
        self.count = count
        self._box = table[:, :4]
        self._weight = table[:, 4]
        self._starts = np.flatnonzero(np.r_[True, np.diff(owners) != 0])

    def compute(self, integrals: tuple[np.ndarray, np.ndarray], windows: np.ndarray,
                only: np.ndarray | None = None, core: float = 0.0) -> np.ndarray:
        """The features of each window (k, 3: x, y, side) of the image whose
        ``integral_image`` is given, as a (k, count) array; with ``only`` (feature
        indices), just those, as (k, len(only)); ``core``: the share of the window's side
        left out at each edge for the contrast the features are divided by."""
        integral, squares = integrals
        windows = np.asarray(windows, dtype=np.float64).reshape(-1, 3)
        box, weight, starts = self._box, self._weight, self._starts
        if only is not None:
            ends = np.r_[self._starts[1:], len(self._box)]
            rows = np.concatenate([np.arange(self._starts[i], ends[i]) for i in only])
            lengths = ends[only] - self._starts[only]
            box, weight = box[rows], weight[rows]
            starts = np.r_[0, np.cumsum(lengths)[:-1]]
        wx, wy, side = windows[:, 0:1], windows[:, 1:2], windows[:, 2:3]
        x0 = np.rint(wx + box[None, :, 0] * side).astype(np.intp)
        y0 = np.rint(wy + box[None, :, 1] * side).astype(np.intp)
        x1 = np.maximum(np.rint(wx + box[None, :, 2] * side).astype(np.intp), x0 + 1)
        y1 = np.maximum(np.rint(wy + box[None, :, 3] * side).astype(np.intp), y0 + 1)
        sums = integral[y1, x1] - integral[y0, x1] - integral[y1, x0] + integral[y0, x0]
        areas = (x1 - x0) * (y1 - y0)
        values = sums / areas * weight[None, :]
        features = np.add.reduceat(values, starts, axis=1)
        # normalise by the window's contrast (with ``core``, of its middle only, as much
        # of the window as a face fills): light level and gain drop out
        margin = np.rint(windows[:, 2] * core).astype(np.intp)
        a, b = (windows[:, :2].astype(np.intp) + margin[:, None]).T
        s = windows[:, 2].astype(np.intp) - 2 * margin
        total = integral[b + s, a + s] - integral[b, a + s] - integral[b + s, a] + integral[b, a]
        total2 = squares[b + s, a + s] - squares[b, a + s] - squares[b + s, a] + squares[b, a]
        mean = total / (s * s)
        spread = np.sqrt(np.maximum(total2 / (s * s) - mean ** 2, 1.0))
        normalised: np.ndarray = features / spread[:, None]
        return normalised


@dataclass(frozen=True, slots=True)
class FaceWindow:
    """A face found: its square window in the image and the cascade's score."""

    x: int
    y: int
    side: int
    score: float

    def window(self) -> Window:
        return (self.x, self.y, self.side)


@dataclass(frozen=True)
class _Stage:
    """One boosted stage as a table of stumps: feature, threshold and the signed vote
    (the stump's weight, + for "face" when the feature is above the threshold)."""

    features: np.ndarray
    thresholds: np.ndarray
    votes: np.ndarray
    threshold: float = 0.0

    @classmethod
    def of(cls, booster: object) -> _Stage:
        features, thresholds, votes = [], [], []
        weights = booster.estimator_weights_  # type: ignore[attr-defined]
        for stump, weight in zip(booster.estimators_, weights, strict=False):  # type: ignore[attr-defined]
            tree = stump.tree_
            if tree.node_count < 3:  # a stump that never split votes the same for all
                continue
            left = int(np.argmax(tree.value[tree.children_left[0]]))
            features.append(int(tree.feature[0]))
            thresholds.append(float(tree.threshold[0]))
            votes.append(float(weight) * (-1.0 if left == 1 else 1.0))
        total = float(np.sum(weights)) or 1.0
        return cls(np.asarray(features, dtype=np.intp), np.asarray(thresholds),
                   np.asarray(votes) / total)

    def score(self, values: np.ndarray) -> np.ndarray:
        """The stage's score of windows whose ``features`` are ``values`` (k, stumps)."""
        above = values > self.thresholds[None, :]
        scores: np.ndarray = np.where(above, self.votes[None, :], -self.votes[None, :]).sum(1)
        return scores


class FaceDetector:
    """A two-stage boosted cascade of Haar-feature stumps over sliding windows.

    Args:
        sizes: the window sides tried, in pixels.
        stride: pixels between windows, as a share of the side.
        features: the Haar feature bank's size.
        stumps: the stumps of the first (quick) and of the second stage.
        seed: the bank's layout and the boosting's randomness.
    """

    def __init__(self, sizes: Sequence[int] = (30, 35, 40, 46), stride: float = 0.1,
                 features: int = 400, stumps: tuple[int, int] = (12, 120),
                 seed: int = 0, refine: int = 2, fine: int = 1) -> None:
        self.sizes = tuple(sizes)
        self.stumps = stumps
        self.stride = stride
        self.bank = HaarFeatures(features, seed)
        self.seed = seed
        self.refine = refine
        self.fine = fine
        self._stages: list[_Stage] = []
        self._refiners: list[_Forest] = []

    def train(self, images: Sequence[np.ndarray], faces: Sequence[Window],
              faceless: Sequence[np.ndarray]) -> None:
        """Learn from ``images`` with one face each at ``faces`` (x, y, side) and from
        ``faceless`` images (every window of them is a negative)."""
        from sklearn.ensemble import AdaBoostClassifier
        from sklearn.tree import DecisionTreeClassifier

        rng = np.random.default_rng([self.seed, 7])
        positives, negatives = [], []
        for image, (x, y, side) in zip(images, faces, strict=True):
            integrals = integral_image(image)
            jitter = [(x + dx, y + dy, side + ds) for dx, dy, ds in
                      rng.integers(-1, 2, (3, 3))]
            jitter = [w for w in jitter if _fits(w, image.shape)]
            positives.append(self.bank.compute(integrals, np.asarray([(x, y, side), *jitter])))
            # windows of the same image well off the face are negatives too
            off = [w for w in self._windows(image.shape) if _overlap(w, (x, y, side)) < 0.3]
            pick = rng.choice(len(off), size=min(6, len(off)), replace=False)
            negatives.append(self.bank.compute(integrals, np.asarray(off)[pick]))
        for image in faceless:
            windows = self._windows(image.shape)
            pick = rng.choice(len(windows), size=min(20, len(windows)), replace=False)
            negatives.append(self.bank.compute(integral_image(image), windows[pick]))
        self._train_refiner(images, faces)
        pos, neg = np.vstack(positives), np.vstack(negatives)
        data = np.vstack((pos, neg))
        labels = np.r_[np.ones(len(pos)), np.zeros(len(neg))]
        self._stages = []
        for stumps, keep in zip(self.stumps, (0.995, 0.5), strict=True):
            booster = AdaBoostClassifier(DecisionTreeClassifier(max_depth=1),
                                         n_estimators=stumps, random_state=self.seed)
            booster.fit(data, labels)
            stage = _Stage.of(booster)
            # the first stage passes nearly every face; the last decides at zero
            threshold = float(np.quantile(stage.score(pos[:, stage.features]), 1.0 - keep)) \
                if keep > 0.5 else 0.0
            stage = _Stage(stage.features, stage.thresholds, stage.votes, threshold)
            self._stages.append(stage)
            # the next stage learns from what passed this one
            passed = stage.score(neg[:, stage.features]) >= threshold
            neg = neg[passed] if passed.any() else neg[:1]
            data = np.vstack((pos, neg))
            labels = np.r_[np.ones(len(pos)), np.zeros(len(neg))]

    def _train_refiner(self, images: Sequence[np.ndarray], faces: Sequence[Window]) -> None:
        """Learn where the face is from a window near it: windows shifted by up to 5
        pixels and resized by up to 6 around each example face, and the shift and
        resizing (as shares of the window's side) that bring each back onto the face;
        a regression forest (extremely randomised trees) on the bank's features. With
        ``fine`` stages, each further forest learns from new windows as far as the
        forests before it bring them (cascaded regression: the later ones learn the
        small errors the first leaves)."""
        self._refiners = []
        if self.refine <= 0:
            return
        from sklearn.ensemble import ExtraTreesRegressor

        for stage in range(1 + self.fine):
            rng = np.random.default_rng([self.seed, 11, stage] if stage else [self.seed, 11])
            data: list[np.ndarray] = []
            targets: list[tuple[float, float, float]] = []
            for image, (x, y, side) in zip(images, faces, strict=True):
                moves = np.column_stack((rng.integers(-5, 6, (12, 2)), rng.integers(-6, 7, 12)))
                windows = [w for w in ((x + a, y + b, side + c) for a, b, c in moves)
                           if _fits(w, image.shape)]
                if not windows:
                    continue
                integrals = integral_image(image)
                if stage:
                    windows = [self._aligned(integrals, w, image.shape) for w in windows]
                data.append(self.bank.compute(integrals, np.asarray(windows)))
                targets.extend(((x - wx) / ws, (y - wy) / ws, (side - ws) / ws)
                               for wx, wy, ws in windows)
            if not data:
                return
            forest = ExtraTreesRegressor(n_estimators=60, min_samples_leaf=3, max_features=0.3,
                                         random_state=self.seed + stage, n_jobs=1)
            forest.fit(np.vstack(data), np.asarray(targets))
            self._refiners.append(_Forest.of(forest, 3, regression=True))

    def _aligned(self, integrals: tuple[np.ndarray, np.ndarray], window: Window,
                 shape: tuple[int, ...]) -> Window:
        """``window`` moved onto the face by the refiners: the first ``refine`` times
        over, each later (finer) one once."""
        if self.refine <= 0:
            return window
        for stage, refiner in enumerate(self._refiners):
            for _ in range(self.refine if stage == 0 else 1):
                x, y, side = window
                vector = self.bank.compute(integrals, np.asarray([window]))[0]
                dx, dy, ds = refiner.shares(refiner.leaves(vector))
                moved = (round(x + dx * side), round(y + dy * side), round(side * (1.0 + ds)))
                if not _fits(moved, shape) or moved == window:
                    break
                window = moved
        return window

    @property
    def trained(self) -> bool:
        return bool(self._stages)

    def _windows(self, shape: tuple[int, ...]) -> np.ndarray:
        height, width = shape[:2]
        windows = []
        for side in self.sizes:
            step = max(1, round(side * self.stride))
            for y in range(0, height - side + 1, step):
                for x in range(0, width - side + 1, step):
                    windows.append((x, y, side))
        return np.asarray(windows, dtype=np.intp).reshape(-1, 3)

    def detect(self, image: np.ndarray) -> list[FaceWindow]:
        """The faces in a grey image, best first (overlapping windows merged)."""
        if not self._stages:
            raise FaceError("the face detector is not trained: call train(...) first")
        windows = self._windows(image.shape)
        if not len(windows):
            return []
        integrals = integral_image(image)
        alive = np.arange(len(windows))
        score = np.zeros(len(windows))
        for stage in self._stages:
            values = stage.score(self.bank.compute(integrals, windows[alive], stage.features))
            keep = values >= stage.threshold
            alive, score = alive[keep], values[keep]
            if not len(alive):
                return []
        found: list[FaceWindow] = []
        for index in np.argsort(-score):
            x, y, side = (int(v) for v in windows[alive[index]])
            if all(_overlap((x, y, side), f.window()) < 0.3 for f in found):
                found.append(FaceWindow(x, y, side, float(score[index])))
        # the best window of a face is often a few pixels off it: the refiner aligns it
        aligned = []
        for face in found:
            x, y, side = self._aligned(integrals, face.window(), image.shape)
            aligned.append(FaceWindow(x, y, side, face.score))
        return aligned


class FaceMemory:
    """Who is who: enrolled people's faces and a random forest over their Haar features.

    Args:
        detector: finds the face in each image (trained).
        threshold: how far (over the person's typical spacing) a face may be from the
            voted person's enrolled views; further, it is a stranger's.
        trees: the forest's size.
        features: the identification bank's size.
        seed: the bank's layout and the forest's randomness.
        core: the share of the face window's side left out at each edge for the contrast
            the features are divided by (the window's corners show the background).
        mirror: enrol each view's mirror image too (the face turned the other way, the
            light from the other side).
    """

    def __init__(self, detector: FaceDetector, threshold: float = 1.0, trees: int = 100,
                 features: int = 2000, seed: int = 0, core: float = 0.2,
                 mirror: bool = True) -> None:
        self.detector = detector
        self.core = core
        self.mirror = mirror
        self.threshold = threshold
        self.trees = trees
        # inside the face's oval: the window's corners show the background
        self.bank = HaarFeatures(features, seed + 1, inset=0.12)
        self.seed = seed
        self._samples: dict[str, list[np.ndarray]] = {}
        self._strangers: list[np.ndarray] = []  #: faces of nobody known (``enrol_strangers``)
        self._forest: _Forest | None = None
        self._names: list[str] = []
        self._labels = np.zeros(0, dtype=np.intp)
        self._telling: tuple[np.ndarray, np.ndarray, np.ndarray] = (
            np.zeros(0, dtype=np.intp), np.zeros(0), np.ones(0))
        self._standard = np.zeros((0, 0))
        self._by_person: list[np.ndarray] = []  #: ``_standard``'s rows of each person
        self._typical = np.ones(0)
        self._held_out: list[np.ndarray] = []  #: each person's held-out enrolment distances
        self._look_thresholds: dict[int, float] = {}

    @property
    def people(self) -> list[str]:
        """The names enrolled."""
        return sorted(self._samples)

    def describe(self, image: np.ndarray, window: Window | None = None) -> np.ndarray | None:
        """The identification features of the face in ``image`` (found by the detector
        unless its ``window`` is given); None when no face is found."""
        if window is None:
            found = self.detector.detect(image)
            if not found:
                return None
            window = found[0].window()
        vector: np.ndarray = self.bank.compute(integral_image(image), np.asarray([window]),
                                               core=self.core)[0]
        return vector

    def enrol(self, name: str, images: Sequence[np.ndarray]) -> int:
        """Add ``name``'s faces (online: the forest is grown again); how many of the
        images had a face."""
        if not name.strip():
            raise FaceError("a person to enrol needs a name")
        described = [views for views in (self._views(image, _SHIFTS) for image in images)
                     if views is not None]
        if not described:
            raise FaceError(f"no face found in the {len(images)} image(s) of {name}; "
                            "enrol with images in which the face is seen from the front")
        self._samples.setdefault(name, []).extend(described)
        self._grow()
        return len(described)

    def enrol_strangers(self, images: Sequence[np.ndarray]) -> int:
        """Learn faces of people who are nobody the robot knows (say, the faces the
        detector was trained on), as one more class of the forest: "a stranger". A face
        the forest votes a stranger's is nobody known, however near a person it lies;
        how many of the images had a face."""
        described = [views for views in (self._views(image, _SHIFTS) for image in images)
                     if views is not None]
        self._strangers.extend(described)
        if self._samples:
            self._grow()
        return len(described)

    def _views(self, image: np.ndarray, shifts: Sequence[tuple[int, int, int]]
               ) -> np.ndarray | None:
        """The features of the face the detector finds in ``image``, of its window moved
        by each of ``shifts`` (x, y, side), and (``mirror``) of the mirrored image's;
        None when no face is found."""
        found = self.detector.detect(image)
        if not found:
            return None
        # the aligned window still wanders by a pixel or so: learn the face so too
        x, y, side = found[0].window()
        windows = [w for w in ((x + a, y + b, side + c) for a, b, c in shifts)
                   if _fits(w, image.shape)]
        views = [self.bank.compute(integral_image(image), np.asarray(windows), core=self.core)]
        if self.mirror:
            # a face seen in a mirror is the same face turned the other way
            width = image.shape[1]
            flipped = [(width - wx - ws, wy, ws) for wx, wy, ws in windows]
            views.append(self.bank.compute(integral_image(image[:, ::-1]), np.asarray(flipped),
                                           core=self.core))
        return np.vstack(views)

    def _grow(self) -> None:
        from sklearn.ensemble import RandomForestClassifier

        self._names = sorted(self._samples)
        blocks = [np.vstack(self._samples[name]) for name in self._names]
        if self._strangers:  # the last class: nobody known
            blocks.append(np.vstack(self._strangers))
        data = np.vstack(blocks)
        labels = np.concatenate([np.full(len(block), index)
                                 for index, block in enumerate(blocks)])
        forest = RandomForestClassifier(n_estimators=self.trees, max_features="sqrt",
                                        random_state=self.seed, n_jobs=1)
        forest.fit(data, labels)
        self._forest = _Forest.of(forest, len(blocks))
        self._labels = labels
        # For rejecting strangers: the features the forest found telling, standardised;
        # a face is far from a person when its nearest enrolled views of them are further
        # than their views are from one another.
        importance = forest.feature_importances_
        telling = np.argsort(-importance)[:_TELLING]
        # each standardised feature weighed by the square root of its importance (the
        # distance's square by the importance: a feature the forest splits on often counts
        # more than one it hardly uses)
        weight = np.sqrt(importance[telling] / max(float(importance[telling].mean()), 1e-12))
        centre = data[:, telling].mean(axis=0)
        scale = (data[:, telling].std(axis=0) + 1e-9) / np.maximum(weight, 1e-6)
        self._telling = (telling, centre, scale)
        self._standard = (data[:, telling] - centre) / scale
        self._by_person = [self._standard[labels == index] for index in range(len(blocks))]
        images = np.concatenate([np.full(len(block), number) for number, block in
                                 enumerate([b for name in self._names
                                            for b in self._samples[name]] + self._strangers)])
        self._held_out = [_held_out_distances(self._standard[labels == index],
                                              images[labels == index])
                          for index in range(len(self._names))]
        # a person's own spacing is the median of their held-out distances (40 images say
        # little about a 97th percentile); how far the tail reaches beyond the median is
        # the household's, from everyone's distances over their own spacing
        spacing = np.asarray([_reach(self._standard[labels == index], distances, 0.5)
                              for index, distances in enumerate(self._held_out)])
        pooled = np.concatenate([distances / max(gap, 1e-9) for distances, gap in
                                 zip(self._held_out, spacing, strict=True)])
        tail = float(np.quantile(pooled, _HELD_OUT)) if len(pooled) else 1.0
        own = spacing * tail
        self._typical = own ** _OWN_REACH * float(np.median(own)) ** (1.0 - _OWN_REACH)
        self._look_thresholds = {}

    def identify(self, image: np.ndarray, window: Window | None = None
                 ) -> tuple[str | None, float]:
        """Whose face ``image`` shows by the forest's vote, and how far it is from that
        person's enrolled views (mean distance to the nearest few, over their typical
        spacing, in the forest's most telling features); (None, far) when it is further
        than ``threshold`` (a stranger), (None, inf) when no face is found."""
        if self._forest is None:
            raise FaceError("nobody is enrolled yet: enrol(name, images) first")
        vector = self.describe(image, window)
        if vector is None:
            return None, math.inf
        votes = self._forest.shares(self._forest.leaves(vector))
        best = int(np.argmax(votes[:len(self._names)]))
        far = self._far(vector, best)
        if self._stranger_voted(votes):
            return None, far
        return (self._names[best], far) if far <= self.threshold else (None, far)

    def _stranger_voted(self, votes: np.ndarray) -> bool:
        """Whether the forest's ``votes`` point to the strangers' class (when there is one)."""
        return len(votes) > len(self._names) and int(np.argmax(votes)) == len(self._names)

    def _far(self, vector: np.ndarray, person: int) -> float:
        """How far a face's features are from ``person``'s enrolled views: the mean
        distance to the nearest few, over the person's reach."""
        telling, centre, scale = self._telling
        gaps = np.linalg.norm(self._by_person[person] - (vector[telling] - centre) / scale,
                              axis=1)
        return float(np.sort(gaps)[:_NEAREST].mean() / self._typical[person])

    def identify_look(self, images: Sequence[np.ndarray]) -> tuple[str | None, float]:
        """Whose face several views of one person show, from the evidence of all of
        them: the person the forest's votes, summed over the views in which a face is
        found, point to, and the median of those views' distances from that person's
        enrolled views (each over their reach, as ``identify`` gives it). The look is
        theirs when that median is within ``threshold`` times the look threshold: the
        ``_LOOK_QUANTILE`` quantile of the same median over looks of as many views
        drawn from the household's held-out enrolment images (``_look_threshold``:
        learnt from the enrolment alone); else (None, median). (None, inf) when no
        view shows a face."""
        if self._forest is None:
            raise FaceError("nobody is enrolled yet: enrol(name, images) first")
        vectors = [vector for vector in (self.describe(image) for image in images)
                   if vector is not None]
        if not vectors:
            return None, math.inf
        votes = np.sum([self._forest.shares(self._forest.leaves(vector))
                        for vector in vectors], axis=0)
        best = int(np.argmax(votes[:len(self._names)]))
        far = float(np.median([self._far(vector, best) for vector in vectors]))
        if self._stranger_voted(votes):
            return None, far
        limit = self.threshold * self._look_threshold(len(vectors))
        return (self._names[best], far) if far <= limit else (None, far)

    def identify_views(self, images: Sequence[np.ndarray]) -> str | None:
        """Whose face several views of one person show (``identify_look``'s name):
        None for a stranger, or when no view shows a face."""
        return self.identify_look(images)[0]

    def _look_threshold(self, views: int) -> float:
        """How far (over the person's reach) a look of ``views`` views may be: the
        ``_LOOK_QUANTILE`` quantile of the median distance of ``views`` held-out
        enrolment images of a person, over ``_LOOK_DRAWS`` draws for each person
        enrolled (seeded: the same memory, the same threshold)."""
        if views not in self._look_thresholds:
            rng = np.random.default_rng([self.seed, 1515, views])
            medians = [float(np.median(rng.choice(distances / reach, views,
                                                  replace=len(distances) < views)))
                       for distances, reach in zip(self._held_out, self._typical,
                                                   strict=True)
                       if len(distances) for _ in range(_LOOK_DRAWS)]
            self._look_thresholds[views] = float(np.quantile(medians, _LOOK_QUANTILE)) \
                if medians else 1.0
        return self._look_thresholds[views]


_INTRODUCTION = re.compile(
    r"\b(?:my name is|my name's|i am called|call me|i'm|i am|this is)\s+"
    r"([a-z][a-z'-]*(?:\s+[a-z][a-z'-]*)?)", re.IGNORECASE)
_NOT_NAMES = frozenset({"a", "an", "the", "here", "back", "fine", "hungry", "thirsty",
                        "tired", "not", "very", "so", "ok", "okay", "done", "ready", "sorry",
                        "looking", "going", "home", "glad", "happy", "good", "well", "please",
                        "thanks", "and", "i", "from"})


def introduced_name(utterance: str) -> str | None:
    """The name a person gives for themselves in ``utterance`` ("my name is Maria",
    "I'm Adel", "call me Sam"), capitalised; None when the sentence introduces nobody
    ("I'm thirsty"). A second word is kept only after "my name is" / "call me"
    ("my name is Anna Maria")."""
    match = _INTRODUCTION.search(utterance.strip().rstrip(".!?"))
    if match is None:
        return None
    words = match.group(1).split()
    if words[0].lower() in _NOT_NAMES:
        return None
    lead = match.group(0)[: match.start(1) - match.start(0)].strip().lower()
    if lead not in ("my name is", "call me") or words[-1].lower() in _NOT_NAMES:
        words = words[:1]
    return " ".join(word.capitalize() for word in words)


class Acquaintances:
    """The people the robot has met by name: a person says "my name is ..." in front of
    the robot, the head camera's views of their face are enrolled under that name
    (CAESAR §2.4's online enrolment), and later views of them are recognised.

    Args:
        memory: makes the face memory on first use (training a detector takes a while:
            a robot nobody introduces themselves to never trains one).
    """

    def __init__(self, memory: Callable[[], FaceMemory]) -> None:
        self._make = memory
        self._memory: FaceMemory | None = None

    @property
    def memory(self) -> FaceMemory:
        if self._memory is None:
            self._memory = self._make()
        return self._memory

    @property
    def people(self) -> list[str]:
        """The names of the people met."""
        return [] if self._memory is None else self._memory.people

    def introduce(self, utterance: str, images: Sequence[np.ndarray]) -> str | None:
        """Enrol the face in ``images`` under the name ``utterance`` gives; the name, or
        None when the sentence gives none or no face is seen in the images."""
        name = introduced_name(utterance)
        if name is None or not images:
            return None
        try:
            self.memory.enrol(name, images)
        except FaceError:
            return None
        return name

    def recognise(self, images: Sequence[np.ndarray]) -> str | None:
        """Who, of the people met, the views show (None: nobody met, or a stranger)."""
        if self._memory is None or not self._memory.people or not images:
            return None
        return self._memory.identify_views(images)


def _held_out_distances(views: np.ndarray, images: np.ndarray) -> np.ndarray:
    """How far new views of a person lie from their enrolled views: each enrolment
    image in turn is held out and its distance to the nearest ``_NEAREST`` views of the
    person's other images taken (cross-validation on the enrolment images alone: no
    stranger's face is needed); empty with one image only."""
    scores = []
    for image in np.unique(images):
        probe, others = views[images == image][0], views[images != image]
        if len(others):
            scores.append(float(np.sort(np.linalg.norm(others - probe, axis=1))
                                [:_NEAREST].mean()))
    return np.asarray(scores)


def _reach(views: np.ndarray, distances: np.ndarray, quantile: float) -> float:
    """The ``quantile`` of a person's held-out ``distances``; with one image only, the
    spread of its own jittered copies stands in."""
    if len(distances):
        return float(np.quantile(distances, quantile))
    gaps = np.linalg.norm(views[:, None, :] - views[None, :, :], axis=2)
    return float(np.median(gaps[gaps > 1e-6])) if np.any(gaps > 1e-6) else 1.0


@dataclass(frozen=True)
class _Forest:
    """A grown forest as padded arrays, walked for all trees at once with numpy
    (scikit-learn's per-call overhead is ~0.1 ms a tree, for one face)."""

    feature: np.ndarray  #: (trees, nodes)
    threshold: np.ndarray
    left: np.ndarray
    right: np.ndarray
    value: np.ndarray  #: (trees, nodes, classes): class shares at each node
    depth: int

    @classmethod
    def of(cls, forest: object, classes: int, regression: bool = False) -> _Forest:
        """The arrays of a fitted scikit-learn forest: a classifier's ``classes`` shares
        at each node, or (``regression``) a regressor's ``classes`` outputs."""
        trees = [estimator.tree_ for estimator in forest.estimators_]  # type: ignore[attr-defined]
        nodes = max(tree.node_count for tree in trees)
        shape = (len(trees), nodes)
        feature = np.zeros(shape, dtype=np.intp)
        threshold = np.zeros(shape)
        left = np.full(shape, -1, dtype=np.intp)
        right = np.full(shape, -1, dtype=np.intp)
        value = np.zeros((*shape, classes))
        for index, tree in enumerate(trees):
            n = tree.node_count
            feature[index, :n] = np.maximum(tree.feature, 0)
            threshold[index, :n] = tree.threshold
            left[index, :n] = tree.children_left
            right[index, :n] = tree.children_right
            if regression:
                value[index, :n, :] = tree.value[:, :, 0]
                continue
            counts = tree.value[:, 0, :]
            value[index, :n, :counts.shape[1]] = counts / np.maximum(
                counts.sum(axis=1, keepdims=True), 1e-12)
        depth = max(int(estimator.get_depth()) for estimator in forest.estimators_)  # type: ignore[attr-defined]
        return cls(feature, threshold, left, right, value, depth)

    def leaves(self, vector: np.ndarray) -> np.ndarray:
        """The leaf each tree sends ``vector`` to."""
        node = np.zeros(len(self.feature), dtype=np.intp)
        active = np.arange(len(self.feature))  # the trees not yet at a leaf
        for _ in range(self.depth):
            at = node[active]
            left = self.left[active, at]
            inner = left >= 0
            if not inner.all():
                active, at, left = active[inner], at[inner], left[inner]
                if not len(active):
                    break
            go_left = vector[self.feature[active, at]] <= self.threshold[active, at]
            node[active] = np.where(go_left, left, self.right[active, at])
        return node

    def shares(self, leaves: np.ndarray) -> np.ndarray:
        """Each identity's share of the trees' votes (a regressor's: the mean outputs)."""
        shares: np.ndarray = self.value[np.arange(len(leaves)), leaves].mean(axis=0)
        return shares


def _fits(window: Window, shape: tuple[int, ...]) -> bool:
    x, y, side = window
    return x >= 0 and y >= 0 and side > 4 and x + side <= shape[1] and y + side <= shape[0]


def _overlap(a: Window | tuple[int, ...], b: Window) -> float:
    """Intersection over union of two square windows."""
    ax, ay, aside = (int(v) for v in a)
    bx, by, bside = b
    w = max(0, min(ax + aside, bx + bside) - max(ax, bx))
    h = max(0, min(ay + aside, by + bside) - max(ay, by))
    inter = w * h
    return inter / (aside * aside + bside * bside - inter)
