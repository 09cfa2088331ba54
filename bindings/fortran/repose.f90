! repose's Fortran 2003 module: the C API (include/repose/repose.h) through iso_c_binding.
!
! Handles are type(c_ptr); every function returns an integer(c_int) code, REPOSE_OK (0) or a REPOSE_ERROR_*
! code, and repose_error_message() gives the thread's last message. The derived types are the C structs
! (bind(c)). What differs from C, for Fortran callers:
!   - strings are Fortran character variables (the wrappers add the C terminator);
!   - repose_particle_from_arrays takes vertices(3, nv) and triangles(3, nt) with 1-based vertex indices;
!   - optional arguments stand for C's NULL.
! Identifiers repose returns (hull faces, poses) are repose's own numbers, from 0, the same as its command
! line and files print. Units, frames and ownership: as in repose.h. Link with -lrepose_c.
module repose
  use, intrinsic :: iso_c_binding
  implicit none
  private

  integer(c_int), parameter, public :: REPOSE_OK = 0, REPOSE_ERROR_NULL_POINTER = 1, REPOSE_ERROR_FILE = 2, &
    REPOSE_ERROR_BAD_MESH = 3, REPOSE_ERROR_BAD_PARAMETER = 4, REPOSE_ERROR_BAD_STATE = 5, &
    REPOSE_ERROR_BAD_INDEX = 6, REPOSE_ERROR_BUFFER_TOO_SMALL = 7, REPOSE_ERROR_OUT_OF_MEMORY = 8, &
    REPOSE_ERROR_INTERNAL = 9
  integer(c_int), parameter, public :: REPOSE_UNITS_SI = 0, REPOSE_UNITS_CGS = 1
  integer(c_int), parameter, public :: REPOSE_INERTIA_EXACT = 0, REPOSE_INERTIA_CONVEX = 1, &
    REPOSE_INERTIA_SHELL = 2
  integer(c_int), parameter, public :: REPOSE_RUNNING = 0, REPOSE_REST = 1, REPOSE_MAX_TIME = 2, &
    REPOSE_MAX_STEPS = 3
  integer(c_int), parameter, public :: REPOSE_CONTACT_FREE_FALL = 0, REPOSE_CONTACT_POINT = 1, &
    REPOSE_CONTACT_LINE = 2, REPOSE_CONTACT_SURFACE = 3, REPOSE_CONTACT_FLIGHT = 4
  integer(c_int), parameter, public :: REPOSE_REST_NONE = 0, REPOSE_REST_SURFACE = 1, REPOSE_REST_POINTS = 2, &
    REPOSE_REST_SMOOTH = 3

  type, bind(c), public :: repose_mesh_options
    real(c_double) :: scale
    integer(c_int) :: inertia, repair, largest_component, has_center_of_mass
    real(c_double) :: center_of_mass(3)
  end type

  type, bind(c), public :: repose_particle_info
    real(c_double) :: mass, volume, length
    real(c_double) :: inertia(9)  ! row-major in C: inertia(3*(r-1)+c) is I(r, c)
    real(c_double) :: center_of_mass(3)
    integer(c_int) :: hull_vertex_count, hull_face_count
  end type

  type, bind(c), public :: repose_state
    real(c_double) :: position(3), orientation(4), velocity(3), angular_velocity(3)
  end type

  type, bind(c), public :: repose_result
    integer(c_int) :: status, rest_kind, rest_face, bounces
    integer(c_long_long) :: steps
    real(c_double) :: time, position(3), orientation(4), down_normal_body(3)
    real(c_double) :: max_penetration, lift, energy_start, energy_end
  end type

  ! Finite friction: the frictional contact phase's energy ledger and every fallback counted by kind
  ! (repose.h's repose_friction_account; all zero with friction infinite).
  type, bind(c), public :: repose_friction_account
    real(c_double) :: friction_work, damping_work, normal_work, drift_corrections, stopping_losses
    real(c_double) :: repositioning, rest_losses, paper_phase_losses, frictionless_motion, impact_losses
    integer(c_int) :: handovers_stalled, handovers_timed_out, bounded_rounds
    integer(c_long_long) :: pyramid_forces, unsolved_forces, unresolved_forces
    integer(c_int) :: zeno_captures, painleve, tip_offs
  end type

  type, bind(c), public :: repose_pose
    integer(c_int) :: face
    real(c_double) :: down_normal_body(3), com_height, barrier, probability
  end type

  public :: repose_error_message, repose_mesh_options_init, repose_particle_load, repose_particle_from_arrays, &
    repose_particle_free, repose_particle_info_get, repose_params_new, repose_params_free, &
    repose_params_set_number, repose_params_set_text, repose_params_get_number, repose_settler_new, &
    repose_settler_free, repose_settler_step, repose_settler_advance_to, repose_settler_run, &
    repose_settler_state, repose_settler_status, repose_settler_contact, repose_settler_contact_points, &
    repose_settler_result, repose_settler_friction_account, repose_settle, repose_poses_new, &
    repose_poses_free, repose_poses_count, repose_poses_get, repose_poses_of_face

  interface
    function c_last_error() bind(c, name="repose_last_error")
      import :: c_ptr
      type(c_ptr) :: c_last_error
    end function
    function repose_mesh_options_init(options) bind(c, name="repose_mesh_options_init")
      import :: c_int, repose_mesh_options
      type(repose_mesh_options), intent(out) :: options
      integer(c_int) :: repose_mesh_options_init
    end function
    function c_particle_load(source, density, options, particle) bind(c, name="repose_particle_load")
      import :: c_int, c_char, c_double, c_ptr
      character(kind=c_char), intent(in) :: source(*)
      real(c_double), value :: density
      type(c_ptr), value :: options
      type(c_ptr), intent(out) :: particle
      integer(c_int) :: c_particle_load
    end function
    function c_particle_from_arrays(vertices, vertex_count, triangles, triangle_count, density, options, name, &
                                    particle) bind(c, name="repose_particle_from_arrays")
      import :: c_int, c_char, c_double, c_ptr, c_size_t
      real(c_double), intent(in) :: vertices(*)
      integer(c_size_t), value :: vertex_count
      integer(c_int), intent(in) :: triangles(*)
      integer(c_size_t), value :: triangle_count
      real(c_double), value :: density
      type(c_ptr), value :: options
      character(kind=c_char), intent(in) :: name(*)
      type(c_ptr), intent(out) :: particle
      integer(c_int) :: c_particle_from_arrays
    end function
    subroutine repose_particle_free(particle) bind(c, name="repose_particle_free")
      import :: c_ptr
      type(c_ptr), value :: particle
    end subroutine
    function repose_particle_info_get(particle, info) bind(c, name="repose_particle_info_get")
      import :: c_int, c_ptr, repose_particle_info
      type(c_ptr), value :: particle
      type(repose_particle_info), intent(out) :: info
      integer(c_int) :: repose_particle_info_get
    end function
    function repose_params_new(units, params) bind(c, name="repose_params_new")
      import :: c_int, c_ptr
      integer(c_int), value :: units
      type(c_ptr), intent(out) :: params
      integer(c_int) :: repose_params_new
    end function
    subroutine repose_params_free(params) bind(c, name="repose_params_free")
      import :: c_ptr
      type(c_ptr), value :: params
    end subroutine
    function c_params_set_number(params, name, value) bind(c, name="repose_params_set_number")
      import :: c_int, c_char, c_double, c_ptr
      type(c_ptr), value :: params
      character(kind=c_char), intent(in) :: name(*)
      real(c_double), value :: value
      integer(c_int) :: c_params_set_number
    end function
    function c_params_set_text(params, name, value) bind(c, name="repose_params_set_text")
      import :: c_int, c_char, c_ptr
      type(c_ptr), value :: params
      character(kind=c_char), intent(in) :: name(*), value(*)
      integer(c_int) :: c_params_set_text
    end function
    function c_params_get_number(params, name, value) bind(c, name="repose_params_get_number")
      import :: c_int, c_char, c_double, c_ptr
      type(c_ptr), value :: params
      character(kind=c_char), intent(in) :: name(*)
      real(c_double), intent(out) :: value
      integer(c_int) :: c_params_get_number
    end function
    function repose_settler_new(particle, params, start, floor_height, settler) bind(c, name="repose_settler_new")
      import :: c_int, c_double, c_ptr, repose_state
      type(c_ptr), value :: particle, params
      type(repose_state), intent(in) :: start
      real(c_double), value :: floor_height
      type(c_ptr), intent(out) :: settler
      integer(c_int) :: repose_settler_new
    end function
    subroutine repose_settler_free(settler) bind(c, name="repose_settler_free")
      import :: c_ptr
      type(c_ptr), value :: settler
    end subroutine
    function repose_settler_step(settler, running) bind(c, name="repose_settler_step")
      import :: c_int, c_ptr
      type(c_ptr), value :: settler
      integer(c_int), intent(out) :: running
      integer(c_int) :: repose_settler_step
    end function
    function repose_settler_advance_to(settler, time, running) bind(c, name="repose_settler_advance_to")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: settler
      real(c_double), value :: time
      integer(c_int), intent(out) :: running
      integer(c_int) :: repose_settler_advance_to
    end function
    function repose_settler_run(settler) bind(c, name="repose_settler_run")
      import :: c_int, c_ptr
      type(c_ptr), value :: settler
      integer(c_int) :: repose_settler_run
    end function
    function repose_settler_state(settler, state, time) bind(c, name="repose_settler_state")
      import :: c_int, c_double, c_ptr, repose_state
      type(c_ptr), value :: settler
      type(repose_state), intent(out) :: state
      real(c_double), intent(out) :: time
      integer(c_int) :: repose_settler_state
    end function
    function repose_settler_status(settler, status) bind(c, name="repose_settler_status")
      import :: c_int, c_ptr
      type(c_ptr), value :: settler
      integer(c_int), intent(out) :: status
      integer(c_int) :: repose_settler_status
    end function
    function repose_settler_contact(settler, contact_type, contact_count) bind(c, name="repose_settler_contact")
      import :: c_int, c_ptr
      type(c_ptr), value :: settler
      integer(c_int), intent(out) :: contact_type, contact_count
      integer(c_int) :: repose_settler_contact
    end function
    function c_settler_contact_points(settler, points, capacity, count) bind(c, name="repose_settler_contact_points")
      import :: c_int, c_double, c_ptr, c_size_t
      type(c_ptr), value :: settler
      real(c_double), intent(out) :: points(*)
      integer(c_size_t), value :: capacity
      integer(c_size_t), intent(out) :: count
      integer(c_int) :: c_settler_contact_points
    end function
    function repose_settler_result(settler, result) bind(c, name="repose_settler_result")
      import :: c_int, c_ptr, repose_result
      type(c_ptr), value :: settler
      type(repose_result), intent(out) :: result
      integer(c_int) :: repose_settler_result
    end function
    function repose_settler_friction_account(settler, account) &
        bind(c, name="repose_settler_friction_account")
      import :: c_int, c_ptr, repose_friction_account
      type(c_ptr), value :: settler
      type(repose_friction_account), intent(out) :: account
      integer(c_int) :: repose_settler_friction_account
    end function
    function repose_settle(particle, params, start, floor_height, result) bind(c, name="repose_settle")
      import :: c_int, c_double, c_ptr, repose_state, repose_result
      type(c_ptr), value :: particle, params
      type(repose_state), intent(in) :: start
      real(c_double), value :: floor_height
      type(repose_result), intent(out) :: result
      integer(c_int) :: repose_settle
    end function
    function repose_poses_new(particle, persistence, poses) bind(c, name="repose_poses_new")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: particle
      real(c_double), value :: persistence
      type(c_ptr), intent(out) :: poses
      integer(c_int) :: repose_poses_new
    end function
    subroutine repose_poses_free(poses) bind(c, name="repose_poses_free")
      import :: c_ptr
      type(c_ptr), value :: poses
    end subroutine
    function repose_poses_count(poses, count) bind(c, name="repose_poses_count")
      import :: c_int, c_ptr
      type(c_ptr), value :: poses
      integer(c_int), intent(out) :: count
      integer(c_int) :: repose_poses_count
    end function
    function repose_poses_get(poses, index, pose) bind(c, name="repose_poses_get")
      import :: c_int, c_ptr, repose_pose
      type(c_ptr), value :: poses
      integer(c_int), value :: index
      type(repose_pose), intent(out) :: pose
      integer(c_int) :: repose_poses_get
    end function
    function repose_poses_of_face(poses, face, pose) bind(c, name="repose_poses_of_face")
      import :: c_int, c_ptr
      type(c_ptr), value :: poses
      integer(c_int), value :: face
      integer(c_int), intent(out) :: pose
      integer(c_int) :: repose_poses_of_face
    end function
    function c_strlen(s) bind(c, name="strlen")
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
      integer(c_size_t) :: c_strlen
    end function
  end interface

contains

  ! The text with C's terminator.
  pure function c_string(text) result(out)
    character(len=*), intent(in) :: text
    character(kind=c_char, len=len(text) + 1) :: out
    out = text // c_null_char
  end function

  ! The last failure's message on this thread.
  function repose_error_message() result(message)
    character(len=:), allocatable :: message
    character(kind=c_char), pointer :: chars(:)
    type(c_ptr) :: p
    integer :: i, n
    p = c_last_error()
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate(character(len=n) :: message)
    do i = 1, n
      message(i:i) = chars(i)
    end do
  end function

  ! A particle from a mesh file or a shape spec ("box:x=1,y=2,z=3").
  function repose_particle_load(source, density, particle, options) result(code)
    character(len=*), intent(in) :: source
    real(c_double), intent(in) :: density
    type(c_ptr), intent(out) :: particle
    type(repose_mesh_options), intent(in), optional, target :: options
    integer(c_int) :: code
    type(c_ptr) :: o
    o = c_null_ptr
    if (present(options)) o = c_loc(options)
    code = c_particle_load(c_string(source), density, o, particle)
  end function

  ! A particle from vertices(3, nv) and triangles(3, nt) of 1-based vertex indices (size(triangles) 0: a point
  ! cloud, with the convex inertia model).
  function repose_particle_from_arrays(vertices, triangles, density, particle, options, name) result(code)
    real(c_double), intent(in) :: vertices(:, :)
    integer(c_int), intent(in) :: triangles(:, :)
    real(c_double), intent(in) :: density
    type(c_ptr), intent(out) :: particle
    type(repose_mesh_options), intent(in), optional, target :: options
    character(len=*), intent(in), optional :: name
    integer(c_int) :: code
    integer(c_int), allocatable :: zero_based(:, :)
    type(c_ptr) :: o
    o = c_null_ptr
    if (present(options)) o = c_loc(options)
    if (size(vertices, 1) /= 3 .or. size(triangles, 1) /= 3) then
      code = REPOSE_ERROR_BAD_MESH  ! C never sees it: no message is recorded
      return
    end if
    allocate(zero_based(3, size(triangles, 2)))
    zero_based = triangles - 1
    if (present(name)) then
      code = c_particle_from_arrays(vertices, int(size(vertices, 2), c_size_t), zero_based, &
                                    int(size(triangles, 2), c_size_t), density, o, c_string(name), particle)
    else
      code = c_particle_from_arrays(vertices, int(size(vertices, 2), c_size_t), zero_based, &
                                    int(size(triangles, 2), c_size_t), density, o, c_string("arrays"), particle)
    end if
  end function

  function repose_params_set_number(params, name, value) result(code)
    type(c_ptr), intent(in) :: params
    character(len=*), intent(in) :: name
    real(c_double), intent(in) :: value
    integer(c_int) :: code
    code = c_params_set_number(params, c_string(name), value)
  end function

  function repose_params_set_text(params, name, value) result(code)
    type(c_ptr), intent(in) :: params
    character(len=*), intent(in) :: name, value
    integer(c_int) :: code
    code = c_params_set_text(params, c_string(name), c_string(value))
  end function

  function repose_params_get_number(params, name, value) result(code)
    type(c_ptr), intent(in) :: params
    character(len=*), intent(in) :: name
    real(c_double), intent(out) :: value
    integer(c_int) :: code
    code = c_params_get_number(params, c_string(name), value)
  end function

  ! The points on the floor (world), points(1:3, 1:count): as repose_settler_contact_points in C, with the
  ! capacity size(points, 2).
  function repose_settler_contact_points(settler, points, count) result(code)
    type(c_ptr), intent(in) :: settler
    real(c_double), intent(out) :: points(:, :)
    integer, intent(out) :: count
    integer(c_int) :: code
    integer(c_size_t) :: n
    if (size(points, 1) /= 3) then
      code = REPOSE_ERROR_BUFFER_TOO_SMALL  ! points must be (3, capacity); C never sees it: no message
      count = 0
      return
    end if
    code = c_settler_contact_points(settler, points, int(size(points, 2), c_size_t), n)
    count = int(n)
  end function

end module repose
