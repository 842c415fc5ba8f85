!> Unit tests of the nodal conditions: a planar rigid wall (frictionless and
!> sticking: landing exactly on the plane, impulse, wall work, release) and
!> symmetry-plane velocity projection, and the axis of an axisymmetric
!> calculation (no node crosses r = 0).
program test_nodal
  use udar_kinds, only: rk
  use udar_strings, only: r2s
  use udar_domain, only: domain_t
  use udar_config, only: wall_frictionless, wall_sticking, wall_coulomb, geometry_axisymmetric
  use udar_nodal, only: apply_rigid_walls, apply_velocity_conditions, update_positions, apply_axis
  use udar_exact_sum, only: exact_limbs, exact_value
  use udar_kinds, only: i8
  use unit_checks, only: check, check_summary
  implicit none
  type(domain_t) :: dom
  real(rk) :: work, dt, force

  dt = 1.0e-6_rk
  ! two nodes above a wall z = 0 (normal +z): node 1 would cross it, node 2 leaves it
  call two_nodes(dom)
  dom%walls(1)%wall_type = wall_frictionless
  call walls(dom, dt, work, force)
  call update_positions(dom, dt)
  call check('frictionless_lands_on_wall', abs(dom%nd_x(3,1)) < 1e-18_rk, 'z = '//r2s(dom%nd_x(3,1))//' m')
  call check('frictionless_keeps_tangential', dom%nd_v(1,1) == 3.0_rk .and. dom%nd_v(2,1) == -1.0_rk, &
             'v_t = ('//r2s(dom%nd_v(1,1))//', '//r2s(dom%nd_v(2,1))//') m/s')
  ! gap 2e-6 m, dt 1e-6 s: normal velocity -2 m/s (from -10), impulse 2 kg * 8 m/s
  call check('wall_normal_velocity', abs(dom%nd_v(3,1) + 2.0_rk) < 1e-12_rk, 'v_n = '//r2s(dom%nd_v(3,1))//' m/s')
  call check('wall_force_from_impulse', abs(force - 16.0_rk/dt) < 1e-6_rk, &
             'F = '//r2s(force)//' N (impulse / dt = 1.6e7)')
  call check('wall_work', abs(work - 2.0_rk*8.0_rk*(-2.0_rk)) < 1e-12_rk, 'W = '//r2s(work)//' J (impulse x v_n)')
  call check('leaving_node_untouched', all(dom%nd_v(:,2) == [1.0_rk, 0.0_rk, 5.0_rk]), 'node 2 free')

  call two_nodes(dom)
  dom%walls(1)%wall_type = wall_sticking
  call walls(dom, dt, work, force)
  call check('sticking_stops_tangential', dom%nd_v(1,1) == 0.0_rk .and. dom%nd_v(2,1) == 0.0_rk &
             .and. abs(dom%nd_v(3,1) + 2.0_rk) < 1e-12_rk, 'v = ('//r2s(dom%nd_v(1,1))//', '// &
             r2s(dom%nd_v(2,1))//', '//r2s(dom%nd_v(3,1))//') m/s')

  ! Coulomb wall: normal change 8 m/s; mu = 0.2 allows 1.6 m/s of the 3.16 m/s
  ! tangential speed to be removed (slip), mu = 1 stops it (stick)
  call two_nodes(dom)
  dom%walls(1)%wall_type = wall_coulomb
  dom%walls(1)%friction = 0.2_rk
  call walls(dom, dt, work, force)
  call check('coulomb_slip', abs(norm2(dom%nd_v(1:2,1)) - (sqrt(10.0_rk) - 1.6_rk)) < 1e-12_rk .and. &
             abs(dom%nd_v(1,1)/dom%nd_v(2,1) + 3.0_rk) < 1e-12_rk, '|v_t| = '//r2s(norm2(dom%nd_v(1:2,1)))// &
             ' m/s (sqrt(10) - 0.2 x 8), direction kept')
  call check('coulomb_friction_work', abs(work - (2.0_rk*8.0_rk*(-2.0_rk) - 2.0_rk*1.6_rk*(sqrt(10.0_rk) - 1.6_rk))) &
             < 1e-9_rk, 'W = '//r2s(work)//' J (normal + friction)')
  call two_nodes(dom)
  dom%walls(1)%wall_type = wall_coulomb
  dom%walls(1)%friction = 1.0_rk
  call walls(dom, dt, work, force)
  call check('coulomb_stick', all(dom%nd_v(1:2,1) == 0.0_rk), 'tangential velocity removed')

  ! symmetry plane x = 0 and y = 0 at node 1, fixed node 2
  call two_nodes(dom)
  dom%sym_nodes = [1, 1]
  dom%sym_normal = reshape([1.0_rk, 0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.0_rk], [2, 3])   ! rows (1,0,0), (0,1,0)
  dom%fixed_nodes = [2]
  call apply_velocity_conditions(dom)
  call check('symmetry_projection', all(dom%nd_v(:,1) == [0.0_rk, 0.0_rk, -10.0_rk]), &
             'v = ('//r2s(dom%nd_v(1,1))//', '//r2s(dom%nd_v(2,1))//', '//r2s(dom%nd_v(3,1))//')')
  call check('fixed_node', all(dom%nd_v(:,2) == 0.0_rk), 'node 2 at rest')

  ! the axis (x = r = 0) of an axisymmetric calculation: node 1 (x = 1 um,
  ! v_r = -3 m/s: r = -2 um after the step) lands on the axis, v_r = -1 m/s,
  ! work m (v_new - v_r) v_new = 2 x 2 x (-1) = -4 J; node 2 (moving out) untouched
  call two_nodes(dom)
  dom%geometry = geometry_axisymmetric
  dom%nd_x(1,1) = 1.0e-6_rk
  dom%nd_v(1,1) = -3.0_rk
  call axis(dom, dt, work)
  call update_positions(dom, dt)
  call check('axis_lands_on_r0', abs(dom%nd_x(1,1)) < 1e-18_rk .and. abs(dom%nd_v(1,1) + 1.0_rk) < 1e-12_rk, &
             'r = '//r2s(dom%nd_x(1,1))//' m, v_r = '//r2s(dom%nd_v(1,1))//' m/s')
  call check('axis_keeps_axial_velocity', dom%nd_v(2,1) == -1.0_rk .and. dom%nd_v(3,1) == -10.0_rk, 'v_y, v_z kept')
  call check('axis_work', abs(work + 4.0_rk) < 1e-12_rk, 'W = '//r2s(work)//' J')
  call check('axis_leaves_others', all(dom%nd_v(:,2) == [1.0_rk, 0.0_rk, 5.0_rk]), 'node 2 free')
  ! a node found at r < 0 (a contact return) is put back within the step
  dom%nd_x(1,1) = -1.0e-6_rk
  dom%nd_v(1,1) = 0.0_rk
  call axis(dom, dt, work)
  call update_positions(dom, dt)
  call check('axis_puts_back', abs(dom%nd_x(1,1)) < 1e-18_rk, 'r = '//r2s(dom%nd_x(1,1))//' m')
  ! not in 3D
  call two_nodes(dom)
  dom%nd_x(1,1) = 1.0e-6_rk
  dom%nd_v(1,1) = -3.0_rk
  call axis(dom, dt, work)
  call check('axis_not_in_3d', dom%nd_v(1,1) == -3.0_rk .and. work == 0.0_rk, 'v_x = '//r2s(dom%nd_v(1,1)))
  call check_summary()

contains

  !> One wall pass; its work and its force (impulse over dt).
  subroutine walls(d, dt, work, force)
    type(domain_t), intent(inout) :: d
    real(rk), intent(in) :: dt
    real(rk), intent(out) :: work, force
    integer(i8) :: work_acc(0:exact_limbs), impulse_acc(0:exact_limbs, 1)
    work_acc = 0; impulse_acc = 0
    call apply_rigid_walls(d, dt, work_acc, impulse_acc)
    work = exact_value(work_acc)
    force = exact_value(impulse_acc(:,1))/dt
  end subroutine

  !> One axis pass and its work.
  subroutine axis(d, dt, work)
    type(domain_t), intent(inout) :: d
    real(rk), intent(in) :: dt
    real(rk), intent(out) :: work
    integer(i8) :: work_acc(0:exact_limbs)
    work_acc = 0
    call apply_axis(d, dt, work_acc)
    work = exact_value(work_acc)
  end subroutine

  subroutine two_nodes(d)
    type(domain_t), intent(out) :: d
    d%n_nodes = 2
    d%n_owned_nodes = 2
    allocate(d%nd_x(3,2), d%nd_v(3,2), d%nd_mass(2), d%walls(1), d%sym_nodes(0), d%sym_normal(0,3), d%fixed_nodes(0))
    d%nd_x(:,1) = [0.0_rk, 0.0_rk, 2.0e-6_rk]; d%nd_v(:,1) = [3.0_rk, -1.0_rk, -10.0_rk]
    d%nd_x(:,2) = [1.0_rk, 0.0_rk, 0.0_rk];    d%nd_v(:,2) = [1.0_rk, 0.0_rk, 5.0_rk]
    d%nd_mass = 2.0_rk
    d%walls(1)%point = 0.0_rk
    d%walls(1)%normal = [0.0_rk, 0.0_rk, 1.0_rk]
  end subroutine

end program test_nodal
