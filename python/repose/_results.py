"""Result objects: the fields of the CLI's --json as attributes, plus NumPy arrays where a run has series."""
import json

import numpy as np


class Record:
    """A JSON object whose keys are also attributes (nested objects become Records, lists stay lists)."""

    def __init__(self, data):
        object.__setattr__(self, "_data", data)

    def __getattr__(self, name):
        try:
            return _wrap(self._data[name])
        except KeyError:
            raise AttributeError(f"{type(self).__name__} has no field '{name}' "
                                 f"(fields: {', '.join(sorted(self._data))})") from None

    def __getitem__(self, name):
        return _wrap(self._data[name])

    def __contains__(self, name):
        return name in self._data

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self._data))

    def __repr__(self):
        return f"{type(self).__name__}({json.dumps(self._data)[:200]})"

    def to_dict(self):
        """The fields as plain Python objects, exactly as the CLI's --json prints them."""
        return json.loads(json.dumps(self._data))


def _wrap(value):
    if isinstance(value, dict):
        return Record(value)
    if isinstance(value, list):
        return [_wrap(v) for v in value]
    return value


class Series(Record):
    """A run's time series: t, quaternion (w, x, y, z), omega, com and velocity (the centre of mass's; world
    frame), kinetic_energy,
    potential_energy (NumPy arrays, one row per sample), contact (the contact type's name per sample) and
    contact_count."""

    def __getattr__(self, name):
        try:
            return self._data[name]
        except KeyError:
            raise AttributeError(f"Series has no field '{name}' (fields: {', '.join(sorted(self._data))})") from None

    def __len__(self):
        return len(self._data["t"])


class SettleResult(Record):
    """One settle: the fields of `repose settle --json` (status, time_to_rest, rest, phases, energy, impacts,
    ...) and, as `series`, the time series."""

    def __init__(self, summary_json, series=None):
        super().__init__(json.loads(summary_json))
        if series is not None:
            series = dict(series)
            series["contact"] = np.array(series["contact"], dtype=str)
        object.__setattr__(self, "series", Series(series) if series is not None else None)


class Pose(Record):
    """One rest pose: probability, ci95, count, quasi_static_probability, down_normal_body, com_height,
    barrier, face, faces, orientation (w, x, y, z) of its first drop, first_drop."""


class PosesResult(Record):
    """A rest-pose study: the fields of `repose poses --json`, with `poses` as Pose objects."""

    def __init__(self, poses_json):
        super().__init__(json.loads(poses_json))

    @property
    def poses(self):
        return [Pose(p) for p in self._data["poses"]]

    @property
    def probabilities(self):
        """The poses' probabilities, in the order of `poses` (a NumPy array)."""
        return np.array([p["probability"] for p in self._data["poses"]])


class DesignResult(Record):
    """A design: the fields of `repose design --json` (outcomes with target, start and achieved, stop,
    reached, max_error, center_of_mass, centroid, center_of_mass_offset, history, ...) and the design's hull
    as `vertices` (n x 3, the mesh's frame) and `triangles` (m x 3, outward)."""

    def __init__(self, summary_json, vertices, triangles):
        super().__init__(json.loads(summary_json))
        object.__setattr__(self, "vertices", np.array(vertices, dtype=float).reshape(-1, 3))
        object.__setattr__(self, "triangles", np.array(triangles, dtype=np.int64).reshape(-1, 3))

    def achieved(self):
        """The achieved probability of each outcome, in the target's order (numpy array)."""
        return np.array([o["achieved"] for o in self._data["outcomes"]])
