#!/usr/bin/env python3
"""Stone Soup's GNN tracker on the real Paris scene, for the comparison in results/real-adsb/.

    python3 -m venv /tmp/ss && /tmp/ss/bin/pip install stonesoup==1.9.1
    /tmp/ss/bin/python scripts/stonesoup_scene.py            # both scenes
    /tmp/ss/bin/python scripts/stonesoup_scene.py --draws [NAME...]   # the scene drawn again

Configured as `replay --tracker` is for the same sensor (its design, printed in
results/real-adsb/summary.md): a constant-velocity Kalman filter with white acceleration of
density q = 32 m^2/s^3 (from the a_max rule abtrack uses), R = sigma^2 I (50 m on the scene, the
draw's sensor sigma on a draw, read from its design file), a Mahalanobis distance gate
at sqrt(G) (G being abtrack's gate on the squared distance), global-nearest-neighbour assignment,
tracks started by MultiMeasurementInitiator with min_points = M + 1 and deleted by
UpdateTimeStepsDeleter after abtrack's miss counts.

Writes results/real-adsb/stonesoup/<scene>.csv in replay --tracker's layout
(t,track_id,status,x,y; every track Stone Soup reports is confirmed) and <scene>.time (the seconds
one process per scene takes: the imports and the scene). The real-adsb experiment group
scores these files with the same metric code as abtrack's when they exist; nothing else needs
them.

--draws: the scene drawn again (`experiments --only real-adsb` leaves each draw's measurements
and abtrack's design for it in host-tests/target/scene-draws/); each draw, or those NAMEs, is
tracked with the design abtrack printed for it, into results/real-adsb/stonesoup/draws/<NAME>.csv.
"""
import time

START = time.perf_counter()

import csv  # noqa: E402
import datetime  # noqa: E402
import math  # noqa: E402
import re  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
from stonesoup.dataassociator.neighbour import GNNWith2DAssignment  # noqa: E402
from stonesoup.deleter.time import UpdateTimeStepsDeleter  # noqa: E402
from stonesoup.hypothesiser.distance import DistanceHypothesiser  # noqa: E402
from stonesoup.initiator.simple import MultiMeasurementInitiator  # noqa: E402
from stonesoup.measures import Mahalanobis  # noqa: E402
from stonesoup.models.measurement.linear import LinearGaussian  # noqa: E402
from stonesoup.models.transition.linear import (  # noqa: E402
    CombinedLinearGaussianTransitionModel,
    ConstantVelocity,
)
from stonesoup.predictor.kalman import KalmanPredictor  # noqa: E402
from stonesoup.tracker.simple import MultiTargetTracker  # noqa: E402
from stonesoup.types.detection import Detection  # noqa: E402
from stonesoup.types.state import GaussianState  # noqa: E402
from stonesoup.updater.kalman import KalmanUpdater  # noqa: E402

IMPORT_SECONDS = time.perf_counter() - START
ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "host-tests" / "data" / "real" / "scene"
OUT = ROOT / "results" / "real-adsb" / "stonesoup"
DRAWS_IN = ROOT / "host-tests" / "target" / "scene-draws"
DRAWS_OUT = OUT / "draws"

SIGMA_M = 50.0
Q = 32.0
V_MAX = 300.0
# replay --tracker's design for each scene (results/real-adsb/summary.md): gate G on the squared
# Mahalanobis distance, confirm M of N, delete a confirmed track after K misses and a tentative
# one after K_t.
DESIGN = {
    "paris_1400": {"sigma": SIGMA_M, "gate": 13.82, "m": 2, "delete": 4, "delete_tentative": 2},
    "paris_1400_hard": {"sigma": SIGMA_M, "gate": 11.62, "m": 3, "delete": 8, "delete_tentative": 4},
}
EPOCH = datetime.datetime(2021, 10, 7, 14, 0, 0)


def scans(path, sigma):
    """(time, set of detections) per scan time of the file, σ `sigma` per axis."""
    by_t = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            by_t.setdefault(float(row["t"]), []).append((float(row["x"]), float(row["y"])))
    model = LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=np.eye(2) * sigma**2)
    for t in sorted(by_t):
        when = EPOCH + datetime.timedelta(seconds=t)
        yield when, {
            Detection(np.array([[x], [y]]), timestamp=when, measurement_model=model)
            for x, y in by_t[t]
        }


def tracker_for(design):
    sigma = design["sigma"]
    transition = CombinedLinearGaussianTransitionModel([ConstantVelocity(Q), ConstantVelocity(Q)])
    measurement = LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=np.eye(2) * sigma**2)
    predictor = KalmanPredictor(transition)
    updater = KalmanUpdater(measurement)
    gate = math.sqrt(design["gate"])

    def associator():
        return GNNWith2DAssignment(
            DistanceHypothesiser(predictor, updater, measure=Mahalanobis(), missed_distance=gate)
        )

    initiator = MultiMeasurementInitiator(
        prior_state=GaussianState(
            np.zeros((4, 1)), np.diag([sigma**2, V_MAX**2, sigma**2, V_MAX**2])
        ),
        measurement_model=measurement,
        deleter=UpdateTimeStepsDeleter(design["delete_tentative"]),
        data_associator=associator(),
        updater=updater,
        min_points=design["m"] + 1,
    )
    return initiator, UpdateTimeStepsDeleter(design["delete"]), associator(), updater


SENSOR_LINE = re.compile(r"sensor σ ([0-9.]+) m per axis")
DESIGN_LINE = re.compile(
    r"design: gate G ([0-9.]+), .*confirm ([0-9]+) of [0-9]+, "
    r"delete after ([0-9]+) misses \(([0-9]+) tentative\)"
)


def design_of(text):
    """The sensor's σ and the design from replay --tracker's sensor and design lines."""
    sensor, found = SENSOR_LINE.search(text), DESIGN_LINE.search(text)
    if not sensor or not found:
        sys.exit(f"no sensor or design line in: {text!r}")
    gate, m, delete, tentative = found.groups()
    return {
        "sigma": float(sensor.group(1)),
        "gate": float(gate),
        "m": int(m),
        "delete": int(delete),
        "delete_tentative": int(tentative),
    }


def track(design, meas_path):
    """replay --tracker's layout of Stone Soup's tracks on one measurement file."""
    initiator, deleter, associator, updater = tracker_for(design)
    tracker = MultiTargetTracker(
        initiator=initiator,
        deleter=deleter,
        detector=scans(meas_path, design["sigma"]),
        data_associator=associator,
        updater=updater,
    )
    ids = {}
    rows = ["t,track_id,status,x,y"]
    for when, tracks in tracker:
        t = (when - EPOCH).total_seconds()
        for reported in sorted(tracks, key=lambda tr: ids.setdefault(tr.id, len(ids) + 1)):
            sv = reported.state_vector
            rows.append(f"{t:.3f},{ids[reported.id]},confirmed,{float(sv[0]):.2f},{float(sv[2]):.2f}")
    return rows, len(ids)


def run(scene):
    start = time.perf_counter()
    rows, tracks = track(DESIGN[scene], DATA / f"{scene}.meas.csv")
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"{scene}.csv").write_text("\n".join(rows) + "\n")
    # As one process per scene would take: the imports and this scene.
    seconds = IMPORT_SECONDS + time.perf_counter() - start
    (OUT / f"{scene}.time").write_text(f"{seconds:.2f}\n")
    print(f"{scene}: {tracks} tracks, {seconds:.1f} s (imports {IMPORT_SECONDS:.1f} s)", file=sys.stderr)


def run_draw(name):
    start = time.perf_counter()
    design = design_of((DRAWS_IN / f"{name}.design").read_text())
    rows, tracks = track(design, DRAWS_IN / f"{name}.meas.csv")
    DRAWS_OUT.mkdir(parents=True, exist_ok=True)
    (DRAWS_OUT / f"{name}.csv").write_text("\n".join(rows) + "\n")
    print(f"{name}: {tracks} tracks, {time.perf_counter() - start:.1f} s", file=sys.stderr)


if __name__ == "__main__":
    if sys.argv[1:2] == ["--draws"]:
        names = sys.argv[2:] or sorted(p.name[: -len(".meas.csv")] for p in DRAWS_IN.glob("*.meas.csv"))
        if not names:
            sys.exit(f"no draws in {DRAWS_IN}: run `experiments --only real-adsb` first")
        for name in names:
            run_draw(name)
    else:
        for name in sys.argv[1:] or list(DESIGN):
            run(name)
