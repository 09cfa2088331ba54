/* repose's C API: settle a rigid particle on a floor from C, Fortran (bindings/fortran/repose.f90) or any
 * language with a C foreign-function interface. No C++ type crosses it and no exception leaves it.
 *
 * Handles. Every object is an opaque handle made by a *_new / *_load / *_from_arrays call and released by its
 * *_free call (free(NULL) does nothing). A particle is immutable once made: any number of threads may use one
 * particle at the same time. Params, settlers and pose catalogues are per-thread objects: each may be used by
 * one thread at a time, while other threads use theirs. A settler and a pose catalogue keep their particle
 * alive, so the particle's handle may be freed before them.
 *
 * Errors. Every call that can fail returns an int: REPOSE_OK (0) or one of the REPOSE_ERROR_* codes below.
 * repose_last_error() then gives a one-line message naming the argument and the problem ("repose_settler_new:
 * start: the particle's lowest point is 0.02 below the floor (more than the contact band, 0.0125)"); it is
 * kept per thread and stays valid until the next failing call on that thread. On failure no output argument
 * is written and no handle is made.
 *
 * Units. repose computes in any consistent units; gravity sets them. repose_params_new(REPOSE_UNITS_SI, ...)
 * sets g = 9.81 (m, kg, s: lengths in metres, density in kg/m^3, velocities in m/s, times in s, energies in
 * J); REPOSE_UNITS_CGS sets g = 981 (cm, g, s, erg). A mesh's coordinates are in its file's length unit times
 * repose_mesh_options.scale, and must be in the params' length unit.
 *
 * Frames. The floor is the plane z = floor_height of the world frame; gravity points along -z. A particle's
 * body frame has its origin at the centre of mass and the axes of the input mesh (not the principal axes),
 * so a DEM code's orientation of the grain it built from the same vertices is the body -> world rotation
 * repose takes, as a unit quaternion (w, x, y, z). Angular velocities are in the world frame.
 */
#ifndef REPOSE_REPOSE_H
#define REPOSE_REPOSE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define REPOSE_C_API_VERSION 1

/* Return codes. */
#define REPOSE_OK 0
#define REPOSE_ERROR_NULL_POINTER 1     /* a required pointer argument is NULL */
#define REPOSE_ERROR_FILE 2             /* a mesh file cannot be opened */
#define REPOSE_ERROR_BAD_MESH 3         /* the mesh or file cannot make a particle (malformed, open, ...) */
#define REPOSE_ERROR_BAD_PARAMETER 4    /* unknown parameter, value out of range, bad density or option */
#define REPOSE_ERROR_BAD_STATE 5        /* a start state that is not finite, a zero quaternion, below floor */
#define REPOSE_ERROR_BAD_INDEX 6        /* an index out of range */
#define REPOSE_ERROR_BUFFER_TOO_SMALL 7 /* an output array is shorter than the data (count says how long) */
#define REPOSE_ERROR_OUT_OF_MEMORY 8
#define REPOSE_ERROR_INTERNAL 9 /* a failure inside repose; the message says what */

/* Unit systems for repose_params_new. */
#define REPOSE_UNITS_SI 0  /* m, kg, s; g = 9.81 m/s^2 */
#define REPOSE_UNITS_CGS 1 /* cm, g, s; g = 981 cm/s^2 */

/* Inertia models (repose_mesh_options.inertia): where the mass is. */
#define REPOSE_INERTIA_EXACT 0  /* the closed solid the surface bounds, density per volume (default) */
#define REPOSE_INERTIA_CONVEX 1 /* the solid convex hull of the vertices: triangle soups, point clouds */
#define REPOSE_INERTIA_SHELL 2  /* mass on the surface, density per unit area: thin-walled parts */

/* How a run stands or ended (repose_settler_status, repose_result.status). */
#define REPOSE_RUNNING 0
#define REPOSE_REST 1      /* at rest in a static equilibrium */
#define REPOSE_MAX_TIME 2  /* stopped at the time limit (parameter max_time) */
#define REPOSE_MAX_STEPS 3 /* stopped at the step limit (parameter max_steps) */

/* The contact type (section 2.2 of the paper) of repose_settler_contact. */
#define REPOSE_CONTACT_FREE_FALL 0 /* the first descent, without rotation */
#define REPOSE_CONTACT_POINT 1
#define REPOSE_CONTACT_LINE 2
#define REPOSE_CONTACT_SURFACE 3
#define REPOSE_CONTACT_FLIGHT 4 /* off the floor after a rebound, or a toss */

/* What the particle rests on (repose_result.rest_kind). */
#define REPOSE_REST_NONE 0
#define REPOSE_REST_SURFACE 1 /* a planar face of its convex hull, flush with the floor */
#define REPOSE_REST_POINTS 2  /* isolated support points forming a hull face (a jagged grain on its tips) */
#define REPOSE_REST_SMOOTH 3  /* the bottom of a smooth particle */

typedef struct repose_particle repose_particle;
typedef struct repose_params repose_params;
typedef struct repose_settler repose_settler;
typedef struct repose_poses repose_poses;

/* REPOSE_C_API_VERSION of the library linked (a header and a library of different versions differ). */
int repose_c_api_version(void);

/* The last failure's message on this thread ("" if none); owned by repose. */
const char* repose_last_error(void);
/* "REPOSE_OK", "REPOSE_ERROR_BAD_MESH", ...; "unknown code" otherwise. A static string. */
const char* repose_code_name(int code);

/* ---- Particles ----------------------------------------------------------------------------------------- */

/* How a mesh becomes a particle. Fill it with repose_mesh_options_init, then change what differs. */
typedef struct repose_mesh_options {
  double scale;             /* every coordinate is multiplied by this first (a file in mm, run in m: 0.001) */
  int inertia;              /* REPOSE_INERTIA_EXACT, _CONVEX or _SHELL */
  int repair;               /* nonzero: mend holes, winding and duplicates first */
  int largest_component;    /* nonzero: keep only the largest connected component (implies repair) */
  int has_center_of_mass;   /* nonzero: center_of_mass is the known centre of mass, not the uniform one */
  double center_of_mass[3]; /* in the input's coordinates (times scale); must lie inside the convex hull */
} repose_mesh_options;

/* The defaults: scale 1, exact inertia, no repair, the uniform centre of mass. */
int repose_mesh_options_init(repose_mesh_options* options);

/* A particle from a mesh file (STL, OBJ, PLY, OFF; XYZ point clouds with REPOSE_INERTIA_CONVEX) or a
 * built-in shape ("box:x=1,y=2,z=3", "irregular:seed=7", ...; docs/command-line.md), with `density` > 0
 * (mass per volume, per area for the shell model). `options` NULL: the defaults. */
int repose_particle_load(const char* source, double density, const repose_mesh_options* options,
                         repose_particle** particle);

/* A particle from arrays: `vertices` holds vertex_count x, y, z triples; `triangles` holds triangle_count
 * triples of 0-based vertex indices, counter-clockwise seen from outside (NULL with 0 triangles: a point
 * cloud, which needs REPOSE_INERTIA_CONVEX). `name` (NULL: "arrays") starts its error messages. */
int repose_particle_from_arrays(const double* vertices, size_t vertex_count, const int* triangles,
                                size_t triangle_count, double density, const repose_mesh_options* options,
                                const char* name, repose_particle** particle);

void repose_particle_free(repose_particle* particle);

typedef struct repose_particle_info {
  double mass;
  double volume;            /* the solid's (exact) or the convex hull's (convex, shell) */
  double length;            /* L: the diameter of the sphere of the same volume */
  double inertia[9];        /* about the centre of mass, body frame, row-major (mass*length^2) */
  double center_of_mass[3]; /* in the input's coordinates: body = input - center_of_mass */
  int hull_vertex_count;
  int hull_face_count;
} repose_particle_info;

int repose_particle_info_get(const repose_particle* particle, repose_particle_info* info);

/* ---- Parameters ---------------------------------------------------------------------------------------- */

/* The settling parameters, with repose's defaults and the gravity of `units` (REPOSE_UNITS_SI or _CGS). */
int repose_params_new(int units, repose_params** params);
void repose_params_free(repose_params* params);

/* Sets a parameter by its name in repose's parameter table (docs/command-line.md; the CLI option without
 * dashes, with underscores: "damping", "restitution", "friction", "contact_threshold", "max_time", ...),
 * checked against its range at once. The start state (drop_height, drop_speed, velocity, spin) comes from
 * repose_settler_new's `start`, not from here. set_number takes numbers (INFINITY for friction: no slip);
 * set_text takes any parameter as the command line writes it ("adaptive", "inf", "1e-9"). */
int repose_params_set_number(repose_params* params, const char* name, double value);
int repose_params_set_text(repose_params* params, const char* name, const char* value);
/* A number-valued parameter's current value. */
int repose_params_get_number(const repose_params* params, const char* name, double* value);

/* ---- Settling ------------------------------------------------------------------------------------------ */

/* The full state of a rigid body, as a DEM code has it. */
typedef struct repose_state {
  double position[3];    /* centre of mass, world frame (length) */
  double orientation[4]; /* unit quaternion w, x, y, z: body -> world (any nonzero length is normalised) */
  double velocity[3];    /* of the centre of mass, world frame (length/time) */
  double angular_velocity[3]; /* world frame (rad/time) */
} repose_state;

/* Starts a settle from `start` above the floor z = floor_height. A particle moving at the start meets the
 * floor with an impact (restitution and friction from `params`); one at rest on or above it falls, as in the
 * paper. A lowest point up to the contact band (contact_threshold * L) below the floor, as an overlap-based
 * DEM code leaves a grain at first touch, is lifted onto the floor (repose_result.lift says by how much);
 * deeper is REPOSE_ERROR_BAD_STATE. The settler's clock starts at 0. */
int repose_settler_new(const repose_particle* particle, const repose_params* params,
                       const repose_state* start, double floor_height, repose_settler** settler);
void repose_settler_free(repose_settler* settler);

/* One step (shorter if an event is inside it). `running` (may be NULL): 0 once the run has ended. */
int repose_settler_step(repose_settler* settler, int* running);
/* Advances to `time` (a DEM code's own step), ending exactly there unless the run ends first. */
int repose_settler_advance_to(repose_settler* settler, double time, int* running);
/* Runs to the end (rest or a limit). */
int repose_settler_run(repose_settler* settler);

/* The current state in the world frame (as `start`: position of the centre of mass, floor included), and the
 * time since the start (`time` may be NULL). */
int repose_settler_state(const repose_settler* settler, repose_state* state, double* time);
/* REPOSE_RUNNING, REPOSE_REST, REPOSE_MAX_TIME or REPOSE_MAX_STEPS. */
int repose_settler_status(const repose_settler* settler, int* status);
/* The contact type now and how many hull vertices lie within the contact band of the floor. */
int repose_settler_contact(const repose_settler* settler, int* contact_type, int* contact_count);
/* The points on the floor, world frame, as x, y, z triples: at rest the supporting points, before that the
 * hull vertices within the contact band. Writes min(count, capacity) points; *count is the number there are
 * (call with capacity 0 to ask); fewer than *count slots is REPOSE_ERROR_BUFFER_TOO_SMALL. */
int repose_settler_contact_points(const repose_settler* settler, double* points, size_t capacity,
                                  size_t* count);

/* The summary of a run (final once the status is not REPOSE_RUNNING). Positions in the world frame. */
typedef struct repose_result {
  int status;                 /* REPOSE_RUNNING, _REST, _MAX_TIME or _MAX_STEPS */
  int rest_kind;              /* REPOSE_REST_* */
  int rest_face;              /* the hull face it rests on, -1 if none (repose_poses_of_face: its pose) */
  int bounces;                /* impacts followed by a flight */
  long long steps;            /* steps taken (events included) */
  double time;                /* time to rest, or when the run stopped (time) */
  double position[3];         /* centre of mass at the end, world (length) */
  double orientation[4];      /* w, x, y, z at the end: body -> world */
  double down_normal_body[3]; /* body-frame unit direction pointing at the floor at the end */
  double max_penetration;     /* deepest any vertex went below the floor during the run (length) */
  double lift;                /* how far the start was lifted onto the floor (length; 0 if not) */
  double energy_start;        /* kinetic + potential above the floor at the start (energy) */
  double energy_end;
} repose_result;

int repose_settler_result(const repose_settler* settler, repose_result* result);

/* Finite friction: the frictional contact phase's energy ledger beyond the impacts' and every fallback,
 * counted by kind (the C++ FrictionalAccount; `repose settle --json`'s "energy", "fallbacks", "captures").
 * Energies in mass*length^2/time^2. With friction infinite every field is zero. */
typedef struct repose_friction_account {
  double friction_work, damping_work; /* taken by friction and by the damping moment */
  double normal_work;                 /* done on the body by the normal forces between events (signed) */
  double drift_corrections;           /* taken by undoing the velocity drift of points held at rest */
  double stopping_losses;             /* taken by the stopping impulses at points at rest */
  double repositioning;               /* potential energy of moves that are not motion (drift, tip-offs) */
  double rest_losses;                 /* kinetic energy left when the body was declared still */
  double paper_phase_losses;          /* taken by the paper's phase after a hand-over */
  double frictionless_motion;         /* mu = 0: translation and vertical spin kept at rest */
  double impact_losses;               /* taken by every impact (captures and Painleve's included) */
  int handovers_stalled, handovers_timed_out, bounded_rounds;   /* fallbacks */
  long long pyramid_forces, unsolved_forces, unresolved_forces; /* fallbacks (force evaluations) */
  int zeno_captures, painleve, tip_offs;                        /* captures */
} repose_friction_account;

int repose_settler_friction_account(const repose_settler* settler, repose_friction_account* account);

/* Runs a settle to the end: repose_settler_new, _run, _result in one call. */
int repose_settle(const repose_particle* particle, const repose_params* params, const repose_state* start,
                  double floor_height, repose_result* result);

/* ---- Rest poses (quasi-static, exact) ------------------------------------------------------------- */

/* The particle's rest-pose catalogue: its stable hull faces (merged by topological persistence, a length;
 * negative: repose's default, 0 for faceted particles and 1 % of L for smooth ones), each with its exact
 * quasi-static probability (no momentum: the share of uniformly random orientations that roll to it). */
int repose_poses_new(const repose_particle* particle, double persistence, repose_poses** poses);
void repose_poses_free(repose_poses* poses);

typedef struct repose_pose {
  int face;                   /* the pose's lowest stable hull face */
  double down_normal_body[3]; /* body-frame outward normal of `face`, pointing at the floor at rest */
  double com_height;          /* centre of mass above the floor at rest (length) */
  double barrier;     /* centre-of-mass height at the lowest saddle out of the pose (length; inf: none) */
  double probability; /* quasi-static probability; the poses' sum to 1 */
} repose_pose;

int repose_poses_count(const repose_poses* poses, int* count);
/* Pose `index` in 0 .. count-1, ordered by centre-of-mass height (as the CLI numbers them). */
int repose_poses_get(const repose_poses* poses, int index, repose_pose* pose);
/* The pose a hull face belongs to (a settle's rest_face -> its pose): quasi-static rolling from that face. */
int repose_poses_of_face(const repose_poses* poses, int face, int* pose);

#ifdef __cplusplus
}
#endif

#endif /* REPOSE_REPOSE_H */
