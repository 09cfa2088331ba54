! A DEM code's hand-over, from Fortran: a 1 x 2 x 3 cm granite brick (given as vertex and triangle arrays, in
! its own mesh frame) is tossed onto a floor at z = 1 cm with restitution and friction, stepped to rest by
! repose, and its rest pose looked up in the exact quasi-static catalogue.
!
!   settle_grain [REFERENCE]
!
! Prints the result. With REFERENCE (a file of the same run through repose's C++ API, written by
! tests/capi/fortran_reference.cpp) it checks that the results agree and stops with a non-zero code if not.
program settle_grain
  use, intrinsic :: iso_c_binding
  use repose
  implicit none
  real(c_double) :: vertices(3, 8)
  integer(c_int) :: triangles(3, 12)
  type(c_ptr) :: particle, params, settler, poses
  type(repose_state) :: start, now
  type(repose_result) :: result
  type(repose_pose) :: pose
  type(repose_friction_account) :: account
  type(repose_particle_info) :: info
  integer(c_int) :: running, pose_index
  integer :: steps
  real(c_double) :: t, half(3), residual, mgl

  ! The brick's corners in its mesh frame (metres), not centred: repose's body frame has its origin at the
  ! centre of mass and these axes.
  vertices = reshape([0d0, 0d0, 0d0,  0.01d0, 0d0, 0d0,  0.01d0, 0.02d0, 0d0,  0d0, 0.02d0, 0d0, &
                      0d0, 0d0, 0.03d0,  0.01d0, 0d0, 0.03d0,  0.01d0, 0.02d0, 0.03d0,  0d0, 0.02d0, 0.03d0], &
                     [3, 8])
  ! Counter-clockwise seen from outside, 1-based.
  triangles = reshape([1, 3, 2,  1, 4, 3,  5, 6, 7,  5, 7, 8,  1, 2, 6,  1, 6, 5, &
                       2, 3, 7,  2, 7, 6,  3, 4, 8,  3, 8, 7,  4, 1, 5,  4, 5, 8], [3, 12])

  call check(repose_particle_from_arrays(vertices, triangles, 2650d0, particle, name="brick"), "particle")
  call check(repose_particle_info_get(particle, info), "info")
  call check(repose_params_new(REPOSE_UNITS_SI, params), "params")
  call check(repose_params_set_number(params, "restitution", 0.4d0), "restitution")
  call check(repose_params_set_number(params, "friction", 0.5d0), "friction")

  ! The state at hand-over: centre of mass 4 cm above the floor, tilted, moving and spinning.
  start%position = [0.10d0, -0.20d0, 0.05d0]
  start%orientation = [0.9d0, 0.3d0, -0.2d0, 0.1d0]  ! normalised by repose
  start%velocity = [0.15d0, 0.05d0, -0.4d0]
  start%angular_velocity = [2d0, -3d0, 1d0]
  call check(repose_settler_new(particle, params, start, 0.01d0, settler), "settler")
  running = 1
  steps = 0
  do while (running /= 0 .and. steps < 1000000)
    call check(repose_settler_step(settler, running), "step")
    steps = steps + 1
  end do
  call check(repose_settler_state(settler, now, t), "state")
  call check(repose_settler_result(settler, result), "result")
  call check(repose_settler_friction_account(settler, account), "friction account")
  call check(repose_poses_new(particle, -1d0, poses), "poses")
  call check(repose_poses_of_face(poses, result%rest_face, pose_index), "pose of face")
  call check(repose_poses_get(poses, pose_index, pose), "pose")

  print '(a, f10.4, a, i0, a)', 'brick: mass ', 1d3 * info%mass, ' g, ', info%hull_face_count, ' hull faces'
  print '(a, i0, a, i0, a, i0, a, f9.6, a)', 'status ', result%status, ', face ', result%rest_face, &
        ', pose ', pose_index, ', at rest after ', result%time, ' s'
  print '(a, i0, a, i0)', 'steps ', result%steps, ', bounces ', result%bounces
  print '(a, 3f12.7)', 'centre of mass (m)', result%position
  print '(a, 4f11.7)', 'orientation (w, x, y, z)', result%orientation
  print '(a, f9.6, a, es10.3)', 'quasi-static probability of the pose ', pose%probability, &
        ', max penetration (m) ', result%max_penetration

  ! Physics: at rest on a face of the brick, the centre of mass is half an edge above the floor, and the
  ! catalogue says the same height (1e-12 m: a few roundings of centimetre lengths).
  half = [0.005d0, 0.01d0, 0.015d0]
  if (result%status /= REPOSE_REST) call fail("not at rest")
  if (minval(abs(result%position(3) - 0.01d0 - half)) > 1d-12) call fail("centre of mass not half an edge up")
  if (abs(pose%com_height - (result%position(3) - 0.01d0)) > 1d-12) call fail("catalogue height differs")
  if (any(now%position /= result%position)) call fail("state and result disagree")
  ! The energy ledger closes (issue 48: to 1e-6 m g L, L = 3 cm the brick's longest edge): the change of
  ! energy is what its terms took or gave.
  residual = result%energy_end - result%energy_start + account%impact_losses + account%friction_work + &
             account%damping_work - account%normal_work + account%stopping_losses + account%drift_corrections - &
             account%repositioning + account%rest_losses + account%paper_phase_losses + account%frictionless_motion
  mgl = info%mass * 9.81d0 * 0.03d0
  print '(a, es10.3, a, i0, a, i0)', 'energy ledger residual ', residual / mgl, ' m g L; Zeno captures ', &
        account%zeno_captures, ', hand-overs ', account%handovers_stalled + account%handovers_timed_out
  if (abs(residual) > 1d-6 * mgl) call fail("the energy ledger does not close")

  if (command_argument_count() >= 1) call compare_with_reference()

  call repose_poses_free(poses)
  call repose_settler_free(settler)
  call repose_params_free(params)
  call repose_particle_free(particle)

contains

  subroutine check(code, what)
    integer(c_int), intent(in) :: code
    character(len=*), intent(in) :: what
    if (code /= REPOSE_OK) then
      print '(a, a, a, i0, a, a)', 'repose error in ', what, ': code ', code, ': ', repose_error_message()
      error stop 2
    end if
  end subroutine

  subroutine fail(what)
    character(len=*), intent(in) :: what
    print '(a, a)', 'FAILED: ', what
    error stop 1
  end subroutine

  ! The C++ API's run, as tests/capi/fortran_reference.cpp wrote it: status, face, steps, bounces, then time,
  ! position(3), orientation(4) with 17 significant digits (read back exactly). The integers and the
  ! orientation must be identical; the position within 1e-15 m (the C API adds the caller's frame back).
  subroutine compare_with_reference()
    character(len=4096) :: path
    integer :: unit, status, face, ref_steps, bounces, zeno, handovers, painleve
    real(c_double) :: time, position(3), orientation(4), friction_work, normal_work, drift, repositioning
    call get_command_argument(1, path)
    open(newunit=unit, file=trim(path), status='old', action='read')
    read(unit, *) status, face, ref_steps, bounces
    read(unit, *) time, position, orientation
    read(unit, *) friction_work, normal_work, drift, repositioning, zeno, handovers, painleve
    close(unit)
    if (friction_work /= account%friction_work .or. normal_work /= account%normal_work .or. &
        drift /= account%drift_corrections .or. repositioning /= account%repositioning .or. &
        zeno /= account%zeno_captures .or. handovers /= account%handovers_stalled + account%handovers_timed_out &
        .or. painleve /= account%painleve) call fail("the friction account differs from the C++ API's")
    if (status /= result%status .or. face /= result%rest_face .or. ref_steps /= result%steps .or. &
        bounces /= result%bounces) call fail("status, face, steps or bounces differ from the C++ API's")
    if (time /= result%time .or. any(orientation /= result%orientation)) &
      call fail("time or orientation differ from the C++ API's")
    if (maxval(abs(position - result%position)) > 1d-15) call fail("position differs from the C++ API's")
    print '(a)', 'the same as the C++ API: status, face, steps, bounces, time, orientation and the friction &
                 &account identical'
  end subroutine

end program settle_grain
