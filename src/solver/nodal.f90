!> Nodal half of the cycle: explicit central-difference update of velocities
!> and positions, velocity conditions (fixed, symmetry planes) and planar
!> rigid walls. Each rank updates its owned nodes (1..n_owned_nodes); the
!> halo brings the ghosts.
module udar_nodal
  use udar_kinds, only: rk
  use udar_domain, only: domain_t, wall_t
  use udar_config, only: wall_sticking, wall_coulomb, geometry_axisymmetric
  use udar_exact_sum, only: exact_limbs, exact_add
  use udar_kinds, only: i8
  implicit none
  private
  public :: update_velocities, apply_velocity_conditions, apply_rigid_walls, walls_on_points, apply_axis, update_positions, &
            keep_constrained_positions, restore_constrained_positions

contains

  !> v(n+1/2) = v(n-1/2) + dt_v F(n)/m, dt_v the mean of the two half steps.
  subroutine update_velocities(dom, dt_v)
    type(domain_t), intent(inout) :: dom
    real(rk), intent(in) :: dt_v
    integer :: n
    real(rk) :: r
    do n = 1, dom%n_owned_nodes
      ! a node whose elements all became particles has no mass and no force
      r = dt_v/max(dom%nd_mass(n), tiny(1.0_rk))
      dom%nd_v(1,n) = dom%nd_v(1,n) + r*dom%nd_f(1,n)
      dom%nd_v(2,n) = dom%nd_v(2,n) + r*dom%nd_f(2,n)
      dom%nd_v(3,n) = dom%nd_v(3,n) + r*dom%nd_f(3,n)
    end do
  end subroutine

  subroutine apply_velocity_conditions(dom)
    type(domain_t), intent(inout) :: dom
    integer :: k, n
    real(rk) :: vn
    do k = 1, size(dom%sym_nodes)
      n = dom%sym_nodes(k)
      vn = dot_product(dom%nd_v(:,n), dom%sym_normal(k,:))
      dom%nd_v(:,n) = dom%nd_v(:,n) - vn*dom%sym_normal(k,:)
    end do
    do k = 1, size(dom%fixed_nodes)
      dom%nd_v(:,dom%fixed_nodes(k)) = 0.0_rk
    end do
  end subroutine

  !> Positions of the nodes under velocity conditions (each symmetry entry,
  !> then each fixed node), before a pass that may move them (contact).
  subroutine keep_constrained_positions(dom, x_kept)
    type(domain_t), intent(in) :: dom
    real(rk), intent(out) :: x_kept(:,:)   !< (3, size(sym_nodes) + size(fixed_nodes))
    integer :: k, ns
    ns = size(dom%sym_nodes)
    do k = 1, ns
      x_kept(:,k) = dom%nd_x(:,dom%sym_nodes(k))
    end do
    do k = 1, size(dom%fixed_nodes)
      x_kept(:,ns+k) = dom%nd_x(:,dom%fixed_nodes(k))
    end do
  end subroutine

  !> After such a pass the conditions hold again: a symmetry node keeps only
  !> the in-plane part of what the pass did to its position and velocity, a
  !> fixed node none of it; axisymmetric, a node the pass put beyond the
  !> axis goes back onto it (apply_axis takes its velocity in the next step).
  subroutine restore_constrained_positions(dom, x_kept)
    type(domain_t), intent(inout) :: dom
    real(rk), intent(in) :: x_kept(:,:)
    integer :: k, n, ns
    ns = size(dom%sym_nodes)
    do k = 1, ns
      n = dom%sym_nodes(k)
      dom%nd_x(:,n) = dom%nd_x(:,n) - dot_product(dom%nd_x(:,n) - x_kept(:,k), dom%sym_normal(k,:))*dom%sym_normal(k,:)
    end do
    do k = 1, size(dom%fixed_nodes)
      dom%nd_x(:,dom%fixed_nodes(k)) = x_kept(:,ns+k)
    end do
    if (dom%geometry == geometry_axisymmetric) dom%nd_x(1,:) = max(dom%nd_x(1,:), 0.0_rk)
    call apply_velocity_conditions(dom)
  end subroutine

  !> A node that would end the step behind a wall gets the normal velocity
  !> that lands it exactly on the wall (and, sticking, no tangential one).
  !> The impulse gives the wall force; the wall's work is the impulse times
  !> the velocity the node moves with over the step (zero for a node resting
  !> on a fixed wall), so the kinetic energy a node loses when it is stopped
  !> dead stays visible in the energy balance as the discrete impact loss.
  !> Work and normal impulse are added exactly (udar_exact_sum) so that
  !> their global sums do not depend on the partition.
  subroutine apply_rigid_walls(dom, dt, work_acc, impulse_acc)
    type(domain_t), intent(inout) :: dom
    real(rk), intent(in) :: dt      !< the coming step
    integer(i8), intent(inout) :: work_acc(0:exact_limbs)           !< J, wall work (all walls)
    integer(i8), intent(inout) :: impulse_acc(0:exact_limbs, size(dom%walls))  !< N s, normal impulse per wall
    call walls_on_points(dom%walls, dom%n_owned_nodes, dom%nd_x, dom%nd_v, dom%nd_mass, dt, work_acc, impulse_acc)
  end subroutine

  !> The rigid walls' rule (apply_rigid_walls) for n points of masses m at
  !> x (the start of the step) with velocities v (the step's, corrected).
  subroutine walls_on_points(walls, n, x, v, m, dt, work_acc, impulse_acc)
    type(wall_t), intent(in) :: walls(:)
    integer, intent(in) :: n
    real(rk), intent(in) :: x(:,:), m(:), dt
    real(rk), intent(inout) :: v(:,:)
    integer(i8), intent(inout) :: work_acc(0:exact_limbs), impulse_acc(0:exact_limbs, size(walls))
    integer :: iw, k
    real(rk) :: gap, vn, vn_new, vt(3), dvt(3), vt_mag
    do iw = 1, size(walls)
      associate (wall => walls(iw))
        do k = 1, n
          gap = dot_product(x(:,k) - wall%point, wall%normal)
          vn = dot_product(v(:,k), wall%normal)
          if (gap + dt*vn >= 0.0_rk) cycle
          ! lands on the wall at the end of the step (a point found behind it is put back)
          vn_new = -gap/dt
          vt = v(:,k) - vn*wall%normal
          select case (wall%wall_type)
          case (wall_sticking)
            dvt = -vt
          case (wall_coulomb)
            ! tangential impulse at most friction x normal impulse: stick or slide
            vt_mag = norm2(vt)
            if (vt_mag <= wall%friction*(vn_new - vn)) then
              dvt = -vt
            else
              dvt = -(wall%friction*(vn_new - vn)/vt_mag)*vt
            end if
          case default
            dvt = 0.0_rk
          end select
          v(:,k) = vt + dvt + vn_new*wall%normal
          call exact_add(impulse_acc(:,iw), m(k)*(vn_new - vn))
          ! work of the wall's normal and tangential impulses over the point's motion
          call exact_add(work_acc, m(k)*((vn_new - vn)*vn_new + dot_product(dvt, vt + dvt)))
        end do
      end associate
    end do
  end subroutine

  !> Axisymmetric: no node crosses the axis. A node off it (a node of
  !> eroded elements, a ring of debris converging on the axis) that would
  !> end the step at r < 0 lands on the axis instead (r = 0 at the end of
  !> the step; one found at r < 0 is put back), the frictionless wall's
  !> rule: its ring has closed. The work of the radial impulses goes into
  !> work_acc (the wall work of the energy balance). The nodes on the axis
  !> from the start hold it through the velocity conditions.
  subroutine apply_axis(dom, dt, work_acc)
    type(domain_t), intent(inout) :: dom
    real(rk), intent(in) :: dt
    integer(i8), intent(inout) :: work_acc(0:exact_limbs)
    integer :: n
    real(rk) :: vr
    if (dom%geometry /= geometry_axisymmetric) return
    do n = 1, dom%n_owned_nodes
      if (dom%nd_x(1,n) + dt*dom%nd_v(1,n) >= 0.0_rk) cycle
      vr = -dom%nd_x(1,n)/dt
      call exact_add(work_acc, dom%nd_mass(n)*(vr - dom%nd_v(1,n))*vr)
      dom%nd_v(1,n) = vr
    end do
  end subroutine

  subroutine update_positions(dom, dt)
    type(domain_t), intent(inout) :: dom
    real(rk), intent(in) :: dt
    integer :: n
    do n = 1, dom%n_owned_nodes
      dom%nd_x(1,n) = dom%nd_x(1,n) + dt*dom%nd_v(1,n)
      dom%nd_x(2,n) = dom%nd_x(2,n) + dt*dom%nd_v(2,n)
      dom%nd_x(3,n) = dom%nd_x(3,n) + dt*dom%nd_v(3,n)
    end do
  end subroutine
end module udar_nodal
