/* repose's C API used from C (C11): every call, and a documented error for each bad input. The physics is
 * checked against closed forms: a cube's six faces each take 1/6 of the quasi-static probability (symmetry),
 * a box at rest has its centre of mass half an edge above the floor, a particle dropped from rest without
 * spin comes to rest below where it was let go (no horizontal impulse can arise in the paper's touch).
 * Exits non-zero at the first failed check, naming it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "repose/repose.h"

static int failures = 0;

#define CHECK(condition)                                                      \
  do {                                                                        \
    if (!(condition)) {                                                       \
      fprintf(stderr, "%s:%d: FAILED: %s\n", __FILE__, __LINE__, #condition); \
      ++failures;                                                             \
    }                                                                         \
  } while (0)

/* A call that must succeed. */
#define OK(call)                                                                          \
  do {                                                                                    \
    int code_ = (call);                                                                   \
    if (code_ != REPOSE_OK) {                                                             \
      fprintf(stderr, "%s:%d: %s: %s\n", __FILE__, __LINE__, #call, repose_last_error()); \
      exit(1);                                                                            \
    }                                                                                     \
  } while (0)

/* A call that must fail with `code` and a message that contains `text`. */
#define FAILS(call, code, text)                                                                         \
  do {                                                                                                  \
    int code_ = (call);                                                                                 \
    if (code_ != (code) || strstr(repose_last_error(), (text)) == NULL) {                               \
      fprintf(stderr, "%s:%d: %s: got %s \"%s\", expected %s with \"%s\"\n", __FILE__, __LINE__, #call, \
              repose_code_name(code_), repose_last_error(), #code, (text));                             \
      ++failures;                                                                                       \
    }                                                                                                   \
  } while (0)

static const double cube_vertices[] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                                       -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
static const int cube_triangles[] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                     1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};

static void test_particle_and_poses(void) {
  repose_particle* cube = NULL;
  repose_particle_info info;
  repose_poses* poses = NULL;
  int count = 0, i, pose = -1;
  double sum = 0;
  OK(repose_particle_from_arrays(cube_vertices, 8, cube_triangles, 12, 2.0, NULL, "cube", &cube));
  OK(repose_particle_info_get(cube, &info));
  CHECK(fabs(info.volume - 8) < 1e-12 && fabs(info.mass - 16) < 1e-12); /* 2 x 2 x 2 at density 2 */
  CHECK(fabs(info.inertia[0] - 16 * 8 / 12.0) < 1e-12);                 /* m (a^2 + b^2) / 12 */
  CHECK(info.inertia[1] == 0 && info.hull_vertex_count == 8 && info.hull_face_count == 6);
  CHECK(fabs(info.length - cbrt(6 * 8 / acos(-1.0))) < 1e-12);

  OK(repose_poses_new(cube, -1, &poses));
  OK(repose_poses_count(poses, &count));
  CHECK(count == 6);
  for (i = 0; i < count; ++i) {
    repose_pose p;
    OK(repose_poses_get(poses, i, &p));
    CHECK(fabs(p.probability - 1.0 / 6) < 1e-12); /* the basins' areas are exact; 1e-12 covers rounding */
    CHECK(fabs(p.com_height - 1) < 1e-12);
    sum += p.probability;
  }
  CHECK(fabs(sum - 1) < 1e-12);
  OK(repose_poses_of_face(poses, 0, &pose));
  CHECK(pose >= 0 && pose < 6);
  FAILS(repose_poses_get(poses, 6, &(repose_pose){0}), REPOSE_ERROR_BAD_INDEX, "index 6 is not a pose");
  FAILS(repose_poses_of_face(poses, -1, &pose), REPOSE_ERROR_BAD_INDEX, "face -1 is not a hull face");
  repose_poses_free(poses);
  repose_particle_free(cube);
}

static void test_settle(void) {
  repose_particle* box = NULL;
  repose_params* params = NULL;
  repose_settler* settler = NULL;
  repose_state start = {{3, -4, 2.5}, {0.8, 0.3, 0.5, 0.1}, {0, 0, 0}, {0, 0, 0}};
  repose_state now;
  repose_result result, again;
  int running = 1, status = -1, type = -1, n = 0, steps = 0;
  size_t count = 0;
  double points[3 * 8], t = -1, damping = -1;
  OK(repose_particle_load("box:x=1,y=2,z=3", 1, NULL, &box));
  OK(repose_params_new(REPOSE_UNITS_SI, &params));
  OK(repose_params_set_number(params, "damping", 0.05));
  OK(repose_params_get_number(params, "damping", &damping));
  CHECK(damping == 0.05);
  OK(repose_params_set_text(params, "integrator", "adaptive"));

  /* Floor at z = 0.5; the box's lowest corner 1 above it at most: a fall, then the paper's rotation. */
  OK(repose_settler_new(box, params, &start, 0.5, &settler));
  OK(repose_settler_state(settler, &now, &t));
  CHECK(t == 0 && fabs(now.position[0] - 3) < 1e-15 && fabs(now.position[2] - 2.5) < 1e-15);
  OK(repose_settler_advance_to(settler, 0.05, &running));
  OK(repose_settler_state(settler, &now, &t));
  CHECK(running == 1 && fabs(t - 0.05) < 1e-15);
  CHECK(fabs(now.velocity[2] + 9.81 * 0.05) < 1e-9); /* free fall: v = -g t */
  while (running && steps++ < 1000000) OK(repose_settler_step(settler, &running));
  OK(repose_settler_status(settler, &status));
  CHECK(status == REPOSE_REST);
  OK(repose_settler_result(settler, &result));
  CHECK(result.rest_kind == REPOSE_REST_SURFACE && result.rest_face >= 0);
  /* At rest on a face of the 1 x 2 x 3 box: the centre of mass half an edge above the floor. */
  CHECK(fabs(result.position[2] - 0.5 - 0.5) < 1e-12 || fabs(result.position[2] - 0.5 - 1) < 1e-12 ||
        fabs(result.position[2] - 0.5 - 1.5) < 1e-12);
  CHECK(result.lift == 0 && result.max_penetration < 1e-9);
  OK(repose_settler_contact(settler, &type, &n));
  FAILS(repose_settler_contact_points(settler, NULL, 0, &count), REPOSE_ERROR_BUFFER_TOO_SMALL, "room for 0");
  CHECK(count == 4); /* a rectangular face's corners */
  FAILS(repose_settler_contact_points(settler, points, 3, &count), REPOSE_ERROR_BUFFER_TOO_SMALL,
        "room for 3 points, there are 4");
  OK(repose_settler_contact_points(settler, points, 8, &count));
  CHECK(fabs(points[2] - 0.5) < 1e-12 && fabs(points[11] - 0.5) < 1e-12); /* on the floor */
  repose_settler_free(settler);

  /* The one-call form gives the same result, to the bit. */
  OK(repose_settle(box, params, &start, 0.5, &again));
  CHECK(memcmp(again.orientation, result.orientation, sizeof result.orientation) == 0);
  CHECK(again.steps == result.steps && again.time == result.time);

  /* A grain left overlapping the floor by less than the band (5 % of L) is lifted onto it. */
  start.position[2] = 0.5 + 1.5 - 0.01;
  start.orientation[0] = 1, start.orientation[1] = start.orientation[2] = start.orientation[3] = 0;
  OK(repose_settle(box, params, &start, 0.5, &again));
  CHECK(fabs(again.lift - 0.01) < 1e-12 && again.status == REPOSE_REST);
  repose_params_free(params);
  repose_particle_free(box);
}

static void test_errors(void) {
  repose_particle* particle = NULL;
  repose_params* params = NULL;
  repose_settler* settler = NULL;
  repose_result result;
  repose_mesh_options options;
  repose_state start = {{0, 0, 5}, {1, 0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  const int one_triangle[] = {0, 1, 2};
  const int out_of_range[] = {0, 1, 9};

  /* Null pointers: each named. */
  FAILS(repose_particle_load(NULL, 1, NULL, &particle), REPOSE_ERROR_NULL_POINTER, "source is NULL");
  FAILS(repose_particle_load("box:x=2,y=2,z=2", 1, NULL, NULL), REPOSE_ERROR_NULL_POINTER,
        "particle is NULL");
  FAILS(repose_params_new(REPOSE_UNITS_SI, NULL), REPOSE_ERROR_NULL_POINTER, "params is NULL");
  FAILS(repose_settler_step(NULL, NULL), REPOSE_ERROR_NULL_POINTER, "settler is NULL");
  FAILS(repose_poses_count(NULL, NULL), REPOSE_ERROR_NULL_POINTER, "poses is NULL");
  FAILS(repose_particle_info_get(NULL, NULL), REPOSE_ERROR_NULL_POINTER, "particle is NULL");
  CHECK(strncmp(repose_last_error(), "repose_particle_info_get: ", 26) == 0);

  /* Bad meshes and files. */
  FAILS(repose_particle_load("/nonexistent/grain.stl", 1, NULL, &particle), REPOSE_ERROR_FILE,
        "/nonexistent/grain.stl: cannot open");
  FAILS(repose_particle_load("box:x=-1", 1, NULL, &particle), REPOSE_ERROR_BAD_MESH, "box");
  FAILS(repose_particle_from_arrays(cube_vertices, 3, one_triangle, 1, 1, NULL, "sheet", &particle),
        REPOSE_ERROR_BAD_MESH, "sheet: ");
  FAILS(repose_particle_from_arrays(cube_vertices, 3, out_of_range, 1, 1, NULL, "bad", &particle),
        REPOSE_ERROR_BAD_MESH, "triangle 0 refers to vertex 9 of 3");
  FAILS(repose_particle_from_arrays(cube_vertices, 8, cube_triangles, 12, -1, NULL, NULL, &particle),
        REPOSE_ERROR_BAD_PARAMETER, "density must be a finite number > 0");
  OK(repose_mesh_options_init(&options));
  options.inertia = 7;
  FAILS(repose_particle_load("box:x=2,y=2,z=2", 1, &options, &particle), REPOSE_ERROR_BAD_PARAMETER,
        "options.inertia");
  CHECK(particle == NULL); /* no handle on failure */

  /* Bad parameters: unknown, out of range, of the start state, a choice given as a number. */
  OK(repose_params_new(REPOSE_UNITS_CGS, &params));
  FAILS(repose_params_new(5, &params), REPOSE_ERROR_BAD_PARAMETER, "units must be");
  FAILS(repose_params_set_number(params, "dampign", 1), REPOSE_ERROR_BAD_PARAMETER,
        "unknown parameter 'dampign'");
  FAILS(repose_params_set_number(params, "restitution", 1.5), REPOSE_ERROR_BAD_PARAMETER, "restitution");
  FAILS(repose_params_set_number(params, "velocity", 1), REPOSE_ERROR_BAD_PARAMETER, "start state");
  FAILS(repose_params_set_number(params, "integrator", 1), REPOSE_ERROR_BAD_PARAMETER,
        "repose_params_set_text");
  FAILS(repose_params_set_text(params, "integrator", "euler"), REPOSE_ERROR_BAD_PARAMETER, "euler");
  FAILS(repose_params_set_text(params, "damping", "0.1x"), REPOSE_ERROR_BAD_PARAMETER, "must be a number");
  FAILS(repose_params_set_number(params, "max_steps", 2.5), REPOSE_ERROR_BAD_PARAMETER, "whole number");
  OK(repose_params_set_text(params, "friction", "inf"));

  /* Bad states: not finite, a zero quaternion, deeper than the band below the floor. */
  OK(repose_particle_load("box:x=2,y=2,z=2", 1, NULL, &particle));
  start.velocity[0] = NAN;
  FAILS(repose_settler_new(particle, params, &start, 0, &settler), REPOSE_ERROR_BAD_STATE,
        "velocity is not finite");
  start.velocity[0] = 0;
  start.orientation[0] = 0;
  FAILS(repose_settler_new(particle, params, &start, 0, &settler), REPOSE_ERROR_BAD_STATE,
        "nonzero quaternion");
  start.orientation[0] = 1;
  FAILS(repose_settler_new(particle, params, &start, 5, &settler), REPOSE_ERROR_BAD_STATE, "below the floor");
  FAILS(repose_settler_new(particle, params, &start, INFINITY, &settler), REPOSE_ERROR_BAD_STATE,
        "floor_height is not finite");
  CHECK(settler == NULL);
  FAILS(repose_settle(particle, params, &start, 0, NULL), REPOSE_ERROR_NULL_POINTER, "result is NULL");
  OK(repose_settle(particle, params, &start, 0, &result));
  CHECK(result.status == REPOSE_REST);
  CHECK(strcmp(repose_code_name(REPOSE_ERROR_BAD_STATE), "REPOSE_ERROR_BAD_STATE") == 0);
  CHECK(strcmp(repose_code_name(42), "unknown code") == 0);
  repose_particle_free(NULL); /* no-ops */
  repose_settler_free(NULL);
  repose_params_free(params);
  repose_particle_free(particle);
}

int main(void) {
  CHECK(repose_c_api_version() == REPOSE_C_API_VERSION);
  test_particle_and_poses();
  test_settle();
  test_errors();
  if (failures > 0) {
    fprintf(stderr, "%d checks failed\n", failures);
    return 1;
  }
  printf("C API: all checks passed\n");
  return 0;
}
