"""Shared by the unit tests: the study files of the repository, temporary folders, synthetic run folders."""

import json
import os
import shutil
import tempfile
import unittest

from sph_study.common import REPO

STUDIES = os.path.join(REPO, "cases", "studies")


def study_file(name):
    """A study file of cases/studies/."""
    return os.path.join(STUDIES, name)


class TempDirCase(unittest.TestCase):
    """A test with its own temporary folder (self.tmp), removed afterwards."""

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="sph_study_test_")
        self.addCleanup(shutil.rmtree, self.tmp, True)

    def write(self, name, text):
        """A file in the temporary folder; returns its path."""
        path = os.path.join(self.tmp, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(text)
        return path


def write_json(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        json.dump(data, f)


def record_run(run, status="completed", summary=None, **rec):
    """A run folder as execute() leaves it: run.json (with the run's args) and, if given, summary.json."""
    data = {"args": run["args"], "mpi": run["mpi"], "status": status}
    data.update(rec)
    write_json(os.path.join(run["dir"], "run.json"), data)
    if summary is not None:
        write_json(os.path.join(run["dir"], "summary.json"), summary)
