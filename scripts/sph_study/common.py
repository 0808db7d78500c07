"""What every part of the study shares: the repository root (the sph program runs there, reports name
paths relative to it), the JSON files of the run folders (run.json, summary.json) and which wall times
are too short to measure speed."""

import json
import os

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Below this a run's wall time is mostly start-up and timer noise: shown, but flagged, in tables and plots.
NOISE_WALL_S = 1.0


def noisy_wall(t):
    """True for a measured wall time under NOISE_WALL_S."""
    return isinstance(t, (int, float)) and t < NOISE_WALL_S


def read_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def write_json(path, data):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(data, f, indent=2)
        f.write("\n")
    os.replace(tmp, path)
