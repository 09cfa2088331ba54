"""repose's C API (include/repose/repose.h) from Python through ctypes, as a DEM code calls it through the C ABI.

Only what the DEM coupling example needs: a particle from a point cloud (the convex model: the solid convex hull
of the grain's vertices, what a polyhedral DEM grain is), SI parameters by name, a settle from a hand-over state
run to rest, and the rest-pose catalogue. Every call's code is checked; a failure raises ReposeError with the C
API's message.
"""
import ctypes

REPOSE_OK = 0
REPOSE_UNITS_SI = 0
REPOSE_INERTIA_CONVEX = 1
REPOSE_REST = 1


class MeshOptions(ctypes.Structure):
    _fields_ = [("scale", ctypes.c_double), ("inertia", ctypes.c_int), ("repair", ctypes.c_int),
                ("largest_component", ctypes.c_int), ("has_center_of_mass", ctypes.c_int),
                ("center_of_mass", ctypes.c_double * 3)]


class ParticleInfo(ctypes.Structure):
    _fields_ = [("mass", ctypes.c_double), ("volume", ctypes.c_double), ("length", ctypes.c_double),
                ("inertia", ctypes.c_double * 9), ("center_of_mass", ctypes.c_double * 3),
                ("hull_vertex_count", ctypes.c_int), ("hull_face_count", ctypes.c_int)]


class State(ctypes.Structure):
    _fields_ = [("position", ctypes.c_double * 3), ("orientation", ctypes.c_double * 4),
                ("velocity", ctypes.c_double * 3), ("angular_velocity", ctypes.c_double * 3)]


class Result(ctypes.Structure):
    _fields_ = [("status", ctypes.c_int), ("rest_kind", ctypes.c_int), ("rest_face", ctypes.c_int),
                ("bounces", ctypes.c_int), ("steps", ctypes.c_longlong), ("time", ctypes.c_double),
                ("position", ctypes.c_double * 3), ("orientation", ctypes.c_double * 4),
                ("down_normal_body", ctypes.c_double * 3), ("max_penetration", ctypes.c_double),
                ("lift", ctypes.c_double), ("energy_start", ctypes.c_double), ("energy_end", ctypes.c_double)]


class Pose(ctypes.Structure):
    _fields_ = [("face", ctypes.c_int), ("down_normal_body", ctypes.c_double * 3), ("com_height", ctypes.c_double),
                ("barrier", ctypes.c_double), ("probability", ctypes.c_double)]


class ReposeError(RuntimeError):
    pass


class Library:
    """The shared library librepose_c.so, loaded from `path`."""

    def __init__(self, path):
        self.lib = ctypes.CDLL(path)
        lib = self.lib
        P = ctypes.c_void_p
        lib.repose_last_error.restype = ctypes.c_char_p
        lib.repose_code_name.restype = ctypes.c_char_p
        lib.repose_code_name.argtypes = [ctypes.c_int]
        lib.repose_mesh_options_init.argtypes = [ctypes.POINTER(MeshOptions)]
        lib.repose_particle_from_arrays.argtypes = [
            ctypes.POINTER(ctypes.c_double), ctypes.c_size_t, ctypes.POINTER(ctypes.c_int), ctypes.c_size_t,
            ctypes.c_double, ctypes.POINTER(MeshOptions), ctypes.c_char_p, ctypes.POINTER(P)]
        lib.repose_particle_free.argtypes = [P]
        lib.repose_particle_free.restype = None
        lib.repose_particle_info_get.argtypes = [P, ctypes.POINTER(ParticleInfo)]
        lib.repose_params_new.argtypes = [ctypes.c_int, ctypes.POINTER(P)]
        lib.repose_params_free.argtypes = [P]
        lib.repose_params_free.restype = None
        lib.repose_params_set_number.argtypes = [P, ctypes.c_char_p, ctypes.c_double]
        lib.repose_settle.argtypes = [P, P, ctypes.POINTER(State), ctypes.c_double, ctypes.POINTER(Result)]
        lib.repose_poses_new.argtypes = [P, ctypes.c_double, ctypes.POINTER(P)]
        lib.repose_poses_free.argtypes = [P]
        lib.repose_poses_free.restype = None
        lib.repose_poses_count.argtypes = [P, ctypes.POINTER(ctypes.c_int)]
        lib.repose_poses_get.argtypes = [P, ctypes.c_int, ctypes.POINTER(Pose)]
        lib.repose_poses_of_face.argtypes = [P, ctypes.c_int, ctypes.POINTER(ctypes.c_int)]

    def check(self, code):
        if code != REPOSE_OK:
            raise ReposeError("%s: %s" % (self.lib.repose_code_name(code).decode(),
                                          self.lib.repose_last_error().decode()))

    def convex_particle(self, vertices, density, name):
        """A particle that is the solid convex hull of `vertices` (a list of (x, y, z))."""
        flat = (ctypes.c_double * (3 * len(vertices)))(*[c for v in vertices for c in v])
        options = MeshOptions()
        self.check(self.lib.repose_mesh_options_init(ctypes.byref(options)))
        options.inertia = REPOSE_INERTIA_CONVEX
        handle = ctypes.c_void_p()
        self.check(self.lib.repose_particle_from_arrays(flat, len(vertices), None, 0, density, ctypes.byref(options),
                                                        name.encode(), ctypes.byref(handle)))
        return handle

    def info(self, particle):
        out = ParticleInfo()
        self.check(self.lib.repose_particle_info_get(particle, ctypes.byref(out)))
        return out

    def params(self, **numbers):
        handle = ctypes.c_void_p()
        self.check(self.lib.repose_params_new(REPOSE_UNITS_SI, ctypes.byref(handle)))
        for name, value in numbers.items():
            self.check(self.lib.repose_params_set_number(handle, name.encode(), float(value)))
        return handle

    def settle(self, particle, params, position, orientation, velocity, angular_velocity, floor_height):
        start = State()
        start.position[:] = list(position)
        start.orientation[:] = list(orientation)
        start.velocity[:] = list(velocity)
        start.angular_velocity[:] = list(angular_velocity)
        result = Result()
        self.check(self.lib.repose_settle(particle, params, ctypes.byref(start), floor_height, ctypes.byref(result)))
        return result

    def poses(self, particle):
        """The catalogue as a list of Pose, and the handle (for pose_of_face)."""
        handle = ctypes.c_void_p()
        self.check(self.lib.repose_poses_new(particle, -1.0, ctypes.byref(handle)))
        count = ctypes.c_int()
        self.check(self.lib.repose_poses_count(handle, ctypes.byref(count)))
        out = []
        for i in range(count.value):
            pose = Pose()
            self.check(self.lib.repose_poses_get(handle, i, ctypes.byref(pose)))
            out.append(pose)
        return out, handle

    def pose_of_face(self, poses_handle, face):
        pose = ctypes.c_int()
        self.check(self.lib.repose_poses_of_face(poses_handle, face, ctypes.byref(pose)))
        return pose.value
