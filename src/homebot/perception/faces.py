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
  learnt mirrored, and shifted by a pixel. ``enrol(name, images)`` adds a person online
  (the forest is grown again on everything enrolled: seconds). Before the identification
  features are taken, the brightness plane that best fits the window's middle is taken
  off (Sung and Poggio's lighting correction: a light from one side adds a ramp across
  the face), and they are divided by the contrast left. Whether the face is the voted
  person's at all is a question of nearness, judged against others (cohort
  normalisation, as in speaker verification): its distance to that person's nearest
  enrolled views (in the forest's 800 most telling features, each standardised and
  weighed by the square root of its importance) over its mean distance to the
  ``_COHORT`` nearest others, people and strangers. Faces of people nobody knows
  (``enrol_strangers``: the faces the cascade was trained on, say, by whose they are)
  are those others, and one more class of the forest (it makes the features it finds
  telling sharper; the class does not veto a face). The reach of that ratio is learnt
  from the enrolment alone (``_learn_reach``): each enrolled image held out in turn
  tells how new views of a person lie, each image of a stranger or a person taken with
  everything of its owner left out tells how a newcomer's face lies, and the reach is
  where strangers let in are ``_LET_IN_PER_MISS`` times the faces missed. A bare distance
  with a per-person reach (before), a strangers' class that vetoed, a vote share,
  leaf proximity and a per-person spread model all separated strangers worse.
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
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from homebot.errors import FaceError

__all__ = ["Acquaintances", "FaceDetector", "FaceMemory", "FaceWindow",
           "HaarFeatures", "integral_image", "introduced_name"]

Window = tuple[int, int, int]  #: x, y, side in pixels
_TELLING = 800  #: features the forest rates highest, for the distance to a person's views
_NEAREST = 3  #: enrolled views a face is compared with
_COHORT = 5  #: the nearest others (people, strangers) a face's nearness is judged against
#: the reach lets in strangers (estimated: ``FaceMemory._learn_reach``) this many times as
#: often as it misses the household's faces: the issue's error budgets, 20 % and 10 %
_LET_IN_PER_MISS = 2.0
#: with nobody to compare with (one person, no strangers): the quantile of the held-out
#: enrolment distances that is the reach
_HELD_OUT = 0.95
#: the enrolled windows around each aligned one: x, y, side in pixels (the first is the
#: window itself)
_SHIFTS = ((0, 0, 0), (-1, 0, 0), (1, 0, 0), (0, -1, 0), (0, 1, 0), (-1, -1, 2), (1, 1, -2))
_LOOK_QUANTILE = 0.9  #: of the held-out enrolment looks' distances: a look's threshold
_LOOK_DRAWS = 200  #: held-out enrolment looks drawn per person for that threshold


def integral_image(image: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The integral image of ``image`` and of its square, each padded with a zero row and
    column: the sum over rows r0:r1, columns c0:c1 is I[r1,c1] - I[r0,c1] - I[r1,c0] + I[r0,c0]."""
    values = np.asarray(image, dtype=np.float64)
    padded = np.zeros((values.shape[0] + 1, values.shape[1] + 1))
    squares = np.zeros_like(padded)
    padded[1:, 1:] = values.cumsum(0).cumsum(1)
    squares[1:, 1:] = (values ** 2).cumsum(0).cumsum(1)
    return padded, squares


def moment_integrals(image: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The integral images of ``image`` times each pixel's column and times its row
    (padded as ``integral_image``'s): with the plain one, the best-fit brightness plane
    of any rectangle in a few look-ups."""
    values = np.asarray(image, dtype=np.float64)
    rows, columns = np.indices(values.shape, dtype=np.float64)
    by_column = np.zeros((values.shape[0] + 1, values.shape[1] + 1))
    by_row = np.zeros_like(by_column)
    by_column[1:, 1:] = (values * columns).cumsum(0).cumsum(1)
    by_row[1:, 1:] = (values * rows).cumsum(0).cumsum(1)
    return by_column, by_row


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
        self._subsets: dict[bytes, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}

    def _subset(self, only: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The rectangles, weights and feature starts of the features ``only`` (kept:
        a cascade stage asks for the same ones at every image)."""
        key = only.tobytes()
        if key not in self._subsets:
            ends = np.r_[self._starts[1:], len(self._box)]
            rows = np.concatenate([np.arange(self._starts[i], ends[i]) for i in only])
            lengths = ends[only] - self._starts[only]
            self._subsets[key] = (self._box[rows], self._weight[rows],
                                  np.r_[0, np.cumsum(lengths)[:-1]])
        return self._subsets[key]

    def compute(self, integrals: tuple[np.ndarray, np.ndarray], windows: np.ndarray,
                only: np.ndarray | None = None, core: float = 0.0,
                moments: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
        """The features of each window (k, 3: x, y, side) of the image whose
        ``integral_image`` is given, as a (k, count) array; with ``only`` (feature
        indices), just those, as (k, len(only)); ``core``: the share of the window's side
        left out at each edge for the contrast the features are divided by. With the
        image's ``moment_integrals``, the brightness plane that best fits the window's
        middle is taken off first (Sung and Poggio's lighting correction): a light from
        one side adds a ramp across the face that the contrast alone leaves in."""
        integral, squares = integrals
        windows = np.asarray(windows, dtype=np.float64).reshape(-1, 3)
        box, weight, starts = self._box, self._weight, self._starts
        if only is not None:
            box, weight, starts = self._subset(np.asarray(only, dtype=np.intp))
        wx, wy, side = windows[:, 0:1], windows[:, 1:2], windows[:, 2:3]
        x0 = np.rint(wx + box[None, :, 0] * side).astype(np.intp)
        y0 = np.rint(wy + box[None, :, 1] * side).astype(np.intp)
        x1 = np.maximum(np.rint(wx + box[None, :, 2] * side).astype(np.intp), x0 + 1)
        y1 = np.maximum(np.rint(wy + box[None, :, 3] * side).astype(np.intp), y0 + 1)
        sums = integral[y1, x1] - integral[y0, x1] - integral[y1, x0] + integral[y0, x0]
        means = sums / ((x1 - x0) * (y1 - y0))
        # normalise by the window's contrast (with ``core``, of its middle only, as much
        # of the window as a face fills): light level and gain drop out
        margin = np.rint(windows[:, 2] * core).astype(np.intp)
        a, b = (windows[:, :2].astype(np.intp) + margin[:, None]).T
        s = windows[:, 2].astype(np.intp) - 2 * margin
        n = s * s

        def region(table: np.ndarray) -> np.ndarray:
            total: np.ndarray = table[b + s, a + s] - table[b, a + s] - table[b + s, a] \
                + table[b, a]
            return total

        mean = region(integral) / n
        variance = region(squares) / n - mean ** 2
        if moments is not None:
            # the plane I = mean + slope_x (x - x̄) + slope_y (y - ȳ), by least squares
            # over the middle (the pixel grid makes the two slopes independent)
            centre_x, centre_y = a + (s - 1) / 2, b + (s - 1) / 2
            spread_sum = s * s * (s * s - 1) / 12.0  # Σ (x - x̄)² over the middle
            slope_x = (region(moments[0]) - centre_x * region(integral)) / spread_sum
            slope_y = (region(moments[1]) - centre_y * region(integral)) / spread_sum
            plane = mean[:, None] \
                + slope_x[:, None] * ((x0 + x1 - 1) / 2 - centre_x[:, None]) \
                + slope_y[:, None] * ((y0 + y1 - 1) / 2 - centre_y[:, None])
            means = means - plane
            variance = variance - (slope_x ** 2 + slope_y ** 2) * spread_sum / n
        features = np.add.reduceat(means * weight[None, :], starts, axis=1)
        spread = np.sqrt(np.maximum(variance, 1.0))
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
        threshold: how far a face may be from the voted person's enrolled views, as a
            share of the learnt reach (``_far``); further, it is a stranger's.
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
                 mirror: bool = True, flatten: bool = True) -> None:
        self.detector = detector
        self.core = core
        self.flatten = flatten
        self.mirror = mirror
        self.threshold = threshold
        self.trees = trees
        # inside the face's oval: the window's corners show the background
        self.bank = HaarFeatures(features, seed + 1, inset=0.12)
        self.seed = seed
        self._samples: dict[str, list[np.ndarray]] = {}
        self._strangers: list[np.ndarray] = []  #: faces of nobody known (``enrol_strangers``)
        self._stranger_names: list[str] = []  #: whose each of ``_strangers`` is
        self._forest: _Forest | None = None
        self._names: list[str] = []
        self._telling: tuple[np.ndarray, np.ndarray, np.ndarray] = (
            np.zeros(0, dtype=np.intp), np.zeros(0), np.ones(0))
        self._gallery: _Gallery | None = None
        self._reach = 1.0  #: the nearness ratio beyond which a face is nobody known
        self._held_out: list[np.ndarray] = []  #: each person's held-out enrolment ``_far``s
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
        vector: np.ndarray = self._describe(image, np.asarray([window]))[0]
        return vector

    def _describe(self, image: np.ndarray, windows: np.ndarray) -> np.ndarray:
        """The identification features of ``windows`` of ``image``."""
        moments = moment_integrals(image) if self.flatten else None
        return self.bank.compute(integral_image(image), windows, core=self.core,
                                 moments=moments)

    def enrol(self, name: str, images: Sequence[np.ndarray]) -> int:
        """Add ``name``'s faces (online: the forest is grown again); how many of the
        images had a face."""
        return self.enrol_people({name: images})[name]

    def enrol_people(self, faces: Mapping[str, Sequence[np.ndarray]]) -> dict[str, int]:
        """Add several people's faces at once (the forest is grown once, not per
        person); how many of each one's images had a face. Nobody is added when one of
        them has no name or no face."""
        described: dict[str, list[np.ndarray]] = {}
        for name, images in faces.items():
            if not name.strip():
                raise FaceError("a person to enrol needs a name")
            described[name] = [views for views in (self._views(image, _SHIFTS)
                                                   for image in images) if views is not None]
            if not described[name]:
                raise FaceError(f"no face found in the {len(images)} image(s) of {name}; "
                                "enrol with images in which the face is seen from the front")
        for name, views in described.items():
            self._samples.setdefault(name, []).extend(views)
        if described:
            self._grow()
        return {name: len(views) for name, views in described.items()}

    def enrol_strangers(self, images: Sequence[np.ndarray],
                        names: Sequence[str] | None = None) -> int:
        """Learn faces of people who are nobody the robot knows (say, the faces the
        detector was trained on): how near a face is to a person is judged against how
        near it is to them (and they are one more class of the forest, "a stranger",
        which sharpens the features it finds telling). ``names`` says whose each image is
        (the same name, the same stranger; without, each image is a stranger of its own);
        how many of the images had a face."""
        if names is not None and len(names) != len(images):
            raise FaceError(f"{len(images)} stranger image(s) but {len(names)} name(s): "
                            "give one name per image, or none")
        owners = list(names) if names is not None else \
            [f"stranger {len(self._stranger_names) + index}" for index in range(len(images))]
        described = [(views, owner) for views, owner in
                     zip((self._views(image, _SHIFTS) for image in images), owners, strict=True)
                     if views is not None]
        self._strangers.extend(views for views, _ in described)
        self._stranger_names.extend(owner for _, owner in described)
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
        views = [self._describe(image, np.asarray(windows))]
        if self.mirror:
            # a face seen in a mirror is the same face turned the other way
            width = image.shape[1]
            flipped = [(width - wx - ws, wy, ws) for wx, wy, ws in windows]
            views.append(self._describe(image[:, ::-1], np.asarray(flipped)))
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
        # For nearness: the features the forest found telling, standardised, each weighed
        # by the square root of its importance (the distance's square by the importance:
        # a feature the forest splits on often counts more than one it hardly uses)
        importance = forest.feature_importances_
        telling = np.argsort(-importance)[:_TELLING]
        weight = np.sqrt(importance[telling] / max(float(importance[telling].mean()), 1e-12))
        centre = data[:, telling].mean(axis=0)
        scale = (data[:, telling].std(axis=0) + 1e-9) / np.maximum(weight, 1e-6)
        self._telling = (telling, centre, scale)
        # the gallery: every enrolled image's views, grouped by whose they are (the
        # people, then each stranger)
        strangers = sorted(set(self._stranger_names))
        per_image = [(self._names.index(name), views) for name in self._names
                     for views in self._samples[name]] + \
            [(len(self._names) + strangers.index(owner), views)
             for owner, views in zip(self._stranger_names, self._strangers, strict=True)]
        self._gallery = _Gallery.of([((views[:, telling] - centre) / scale, owner)
                                     for owner, views in per_image],
                                    len(self._names) + len(strangers))
        self._learn_reach([owner for owner, _ in per_image])

    def _learn_reach(self, owners: Sequence[int]) -> None:
        """How near (``_ratio``) a face must be to be a person's, from the enrolment
        alone: each enrolled image of a person is held out in turn and its ratio taken
        against the rest (how new views of them lie); each image of a stranger, and of a
        person, is taken with everything of its owner left out (how a newcomer's face
        lies: the nearest other person stands for the one the forest would vote). The
        reach is where, over those, the share of strangers let in is ``_LET_IN_PER_MISS``
        times the share of the household's faces missed (they cross there)."""
        gallery, people = self._gallery, len(self._names)
        assert gallery is not None
        probes = gallery.rows[gallery.firsts]  # each image's own window, unshifted
        distances = gallery.distances(probes)
        held: list[list[float]] = [[] for _ in range(people)]
        newcomers: list[float] = []
        images_of = np.bincount(np.asarray(owners, dtype=np.intp), minlength=people)
        for image, owner in enumerate(owners):
            # held out: the image's views; a person's only image, just the window itself
            # (its shifted and mirrored views stand in for new ones)
            out = gallery.images == image if images_of[owner] > 1 else \
                np.arange(len(gallery.rows)) == gallery.firsts[image]
            near = gallery.nearest(np.where(out, np.inf, distances[image]))
            if owner < people:
                held[owner].append(_ratio(near, owner))
            alone = gallery.nearest(np.where(gallery.owners == owner, np.inf, distances[image]))
            others = [person for person in range(people) if person != owner]
            if others:
                voted = min(others, key=lambda person: alone[person])
                newcomers.append(_ratio(alone, voted))
        pooled = np.concatenate([np.asarray(ratios) for ratios in held])
        if len(pooled) and newcomers:
            candidates = np.sort(np.r_[pooled, newcomers])
            missed = 1.0 - np.searchsorted(np.sort(pooled), candidates, side="right") / len(pooled)
            let_in = np.searchsorted(np.sort(newcomers), candidates, side="right") / len(newcomers)
            self._reach = float(candidates[np.argmin(np.maximum(_LET_IN_PER_MISS * missed,
                                                                let_in))])
        else:  # nobody to compare with: one person, no strangers
            self._reach = float(np.quantile(pooled, _HELD_OUT))
        self._reach = max(self._reach, 1e-9)
        self._held_out = [np.asarray(ratios) / self._reach for ratios in held]
        self._look_thresholds = {}

    def identify(self, image: np.ndarray, window: Window | None = None
                 ) -> tuple[str | None, float]:
        """Whose face ``image`` shows by the forest's vote, and how far it is from that
        person's enrolled views against others (``_far``: 1 is the reach); (None, far)
        when it is further than ``threshold`` (a stranger), (None, inf) when no face is
        found."""
        if self._forest is None:
            raise FaceError("nobody is enrolled yet: enrol(name, images) first")
        vector = self.describe(image, window)
        if vector is None:
            return None, math.inf
        votes = self._forest.shares(self._forest.leaves(vector))
        best = int(np.argmax(votes[:len(self._names)]))
        far = self._far(vector, best)
        return (self._names[best], far) if far <= self.threshold else (None, far)

    def _far(self, vector: np.ndarray, person: int) -> float:
        """How far a face is from ``person``'s enrolled views, for others' too: its
        ``_ratio`` over the reach (1: as far as a person's face may be)."""
        assert self._gallery is not None
        telling, centre, scale = self._telling
        distances = self._gallery.distances(((vector[telling] - centre) / scale)[None, :])[0]
        return _ratio(self._gallery.nearest(distances), person) / self._reach

    def identify_look(self, images: Sequence[np.ndarray]) -> tuple[str | None, float]:
        """Whose face several views of one person show, from the evidence of all of
        them: the person the forest's votes, summed over the views in which a face is
        found, point to, and the median of those views' distances from that person's
        enrolled views (each ``_far``, as ``identify`` gives it). The look is
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
        limit = self.threshold * self._look_threshold(len(vectors))
        return (self._names[best], far) if far <= limit else (None, far)

    def identify_views(self, images: Sequence[np.ndarray]) -> str | None:
        """Whose face several views of one person show (``identify_look``'s name):
        None for a stranger, or when no view shows a face."""
        return self.identify_look(images)[0]

    def _look_threshold(self, views: int) -> float:
        """How far (``_far``) a look of ``views`` views may be: the
        ``_LOOK_QUANTILE`` quantile of the median distance of ``views`` held-out
        enrolment images of a person, over ``_LOOK_DRAWS`` draws for each person
        enrolled (seeded: the same memory, the same threshold)."""
        if views not in self._look_thresholds:
            rng = np.random.default_rng([self.seed, 1515, views])
            medians = [float(np.median(rng.choice(distances, views,
                                                  replace=len(distances) < views)))
                       for distances in self._held_out
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


def _ratio(nearest: np.ndarray, person: int) -> float:
    """How near a face is to ``person`` against everyone else: its distance to them (the
    mean of the ``_NEAREST`` nearest of their views, ``nearest[person]``) over the mean
    distance to the ``_COHORT`` nearest others (people and strangers); a face of theirs
    is nearer to them than to others, a newcomer's lies about as near to several. With
    nobody else enrolled, the distance itself."""
    others = np.delete(nearest, person)
    others = others[np.isfinite(others)]  # owners left out
    if not len(others):
        return float(nearest[person])
    cohort = float(np.sort(others)[:_COHORT].mean())
    return float(nearest[person]) / max(cohort, 1e-12)


@dataclass(frozen=True)
class _Gallery:
    """Enrolled views (standardised telling features) grouped by whose they are, for the
    distance from a face to each owner: the mean of its ``_NEAREST`` nearest views."""

    rows: np.ndarray  #: (n, d) float32
    norms: np.ndarray  #: (n,) the rows' squared lengths
    owners: np.ndarray  #: (n,) whose each row is
    images: np.ndarray  #: (n,) which enrolled image each row comes from
    firsts: np.ndarray  #: each image's first row (its own window, unshifted)
    layout: np.ndarray  #: (owners, most) each owner's rows, padded with n (a far slot)

    @classmethod
    def of(cls, images: Sequence[tuple[np.ndarray, int]], owners: int) -> _Gallery:
        """The gallery of ``images``: each one's views and owner."""
        rows = np.vstack([views for views, _ in images]).astype(np.float32)
        owner_of = np.concatenate([np.full(len(views), owner) for views, owner in images])
        image_of = np.concatenate([np.full(len(views), index)
                                   for index, (views, _) in enumerate(images)])
        firsts = np.r_[0, np.cumsum([len(views) for views, _ in images])[:-1]]
        members = [np.flatnonzero(owner_of == owner) for owner in range(owners)]
        layout = np.full((owners, max(len(m) for m in members)), len(rows), dtype=np.intp)
        for owner, indices in enumerate(members):
            layout[owner, :len(indices)] = indices
        return cls(rows, np.einsum("ij,ij->i", rows, rows), owner_of, image_of,
                   firsts.astype(np.intp), layout)

    def distances(self, vectors: np.ndarray) -> np.ndarray:
        """(m, n): each of ``vectors``' distance to each row (|a-b|² = |a|² - 2ab + |b|²,
        one matrix product: a face is compared with thousands of views)."""
        vectors = np.asarray(vectors, dtype=np.float32)
        squares = self.norms[None, :] - 2.0 * (vectors @ self.rows.T) \
            + np.einsum("ij,ij->i", vectors, vectors)[:, None]
        distances: np.ndarray = np.sqrt(np.maximum(squares, 0.0)).astype(np.float64)
        return distances

    def nearest(self, distances: np.ndarray) -> np.ndarray:
        """Each owner's mean distance over its ``_NEAREST`` nearest rows (inf for an
        owner all of whose rows are left out, as inf distances)."""
        padded = np.append(distances, np.inf)[self.layout]
        k = min(_NEAREST, padded.shape[1])
        smallest = np.partition(padded, k - 1, axis=1)[:, :k]
        with np.errstate(invalid="ignore"):
            means: np.ndarray = smallest.mean(axis=1)
        return means


@dataclass(frozen=True)
class _Forest:
    """A grown forest as padded arrays, walked compiled (``forest_walk``: scikit-learn's
    per-call overhead is ~0.1 ms a tree, for one face)."""

    feature: np.ndarray  #: (trees, nodes)
    threshold: np.ndarray
    left: np.ndarray
    right: np.ndarray
    value: np.ndarray  #: (trees, nodes, classes): class shares at each node

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
        return cls(feature, threshold, left, right, value)

    def leaves(self, vector: np.ndarray) -> np.ndarray:
        """The leaf each tree sends ``vector`` to (compiled: ``forest_walk``)."""
        from homebot.perception.forest_walk import walk

        leaves: np.ndarray = walk(self.feature, self.threshold, self.left, self.right,
                                  np.ascontiguousarray(vector, dtype=np.float64))
        return leaves

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
