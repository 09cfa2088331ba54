# Type stubs of the repose package (units: the mesh's lengths, seconds, density × volume; see __init__.py).
from typing import Any, Dict, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

Orientation = Union[str, Sequence[float]]  # "identity", "quat:w,x,y,z", "axis-angle:x,y,z,a" or [w, x, y, z]

class Particle:
    @staticmethod
    def load(source: str, density: float = 1.0, units: Optional[str] = None, scale: float = 1.0,
             inertia: str = "exact", repair: bool = False, largest_component: bool = False,
             com: Optional[Sequence[float]] = None) -> Particle: ...
    @staticmethod
    def shape(spec: str, density: float = 1.0) -> Particle: ...
    @staticmethod
    def from_arrays(vertices: npt.ArrayLike, faces: npt.ArrayLike, density: float = 1.0, inertia: str = "exact",
                    repair: bool = False, name: str = "arrays", com: Optional[Sequence[float]] = None) -> Particle: ...
    name: str
    density: float  # mass per volume (per area for inertia="shell")
    mass: float
    volume: float
    length: float  # L, the diameter of the sphere of equal volume
    com: npt.NDArray[np.float64]  # centre of mass in the input mesh's frame
    inertia: npt.NDArray[np.float64]  # 3×3 about the centre of mass, mesh axes (mass·length²)
    principal_moments: npt.NDArray[np.float64]
    principal_axes: npt.NDArray[np.float64]
    inertia_model: str
    vertices: npt.NDArray[np.float64]  # body frame: centre of mass at the origin
    triangles: npt.NDArray[np.int32]
    hull_vertices: npt.NDArray[np.float64]
    hull_faces: list[list[int]]
    hull_normals: npt.NDArray[np.float64]
    bounds: npt.NDArray[np.float64]  # [min, max], body frame
    smooth: bool

class Record:
    def __getattr__(self, name: str) -> Any: ...
    def __getitem__(self, name: str) -> Any: ...
    def to_dict(self) -> dict[str, Any]: ...

class Series(Record):
    t: npt.NDArray[np.float64]
    quaternion: npt.NDArray[np.float64]
    omega: npt.NDArray[np.float64]
    com: npt.NDArray[np.float64]
    kinetic_energy: npt.NDArray[np.float64]
    potential_energy: npt.NDArray[np.float64]
    contact: npt.NDArray[np.str_]
    contact_count: npt.NDArray[np.int32]
    def __len__(self) -> int: ...

class SettleResult(Record):
    status: str
    time_to_rest: float
    series: Optional[Series]

class Pose(Record):
    probability: float
    ci95: list[float]
    count: int
    quasi_static_probability: float

class PosesResult(Record):
    @property
    def poses(self) -> list[Pose]: ...
    @property
    def probabilities(self) -> npt.NDArray[np.float64]: ...

class DesignResult(Record):
    vertices: npt.NDArray[np.float64]
    triangles: npt.NDArray[np.int64]
    reached: bool
    stop: str
    max_error: float
    def achieved(self) -> npt.NDArray[np.float64]: ...

class Settler:
    def __init__(self, particle: Particle, orientation: Orientation = "identity", **params: Any) -> None: ...
    def step(self) -> bool: ...
    def advance_to(self, time: float) -> bool: ...
    def sample(self) -> dict[str, Any]: ...
    @property
    def status(self) -> str: ...
    def result(self) -> SettleResult: ...

def settle(particle: Particle, orientation: Orientation = "identity", *, sample_dt: Optional[float] = None,
           **params: Any) -> SettleResult: ...
def poses(particle: Particle, n: int, *, seed: int = 1, threads: int = 0, method: str = "dynamic",
          damping_ratio: float = 0.05, full_settle: bool = False, velocity_max: float = 0.0,
          spin_max: float = 0.0, persistence: Optional[float] = None, **params: Any) -> PosesResult: ...
def quasi_static(particle: Particle, *, persistence: Optional[float] = None) -> list[Pose]: ...
def design(particle: Particle, target: Any, *, vary: str = "vertices+center-of-mass", mass: str = "follows",
           outcome_angle: float = 30.0, outcome_normals: str = "fixed", com_margin: float = 0.05,
           max_move: float = 0.15, max_step: float = 0.05, min_edge: float = 0.02, min_face: float = 0.001,
           min_margin: float = 0.0, smoothing: float = 0.1, tolerance: float = 1e-4,
           iterations: int = 200, model: str = "quasi-static",
           toss: Optional[Dict[str, Any]] = None) -> DesignResult: ...
