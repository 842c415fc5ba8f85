!> The element passes of the run loop for the domain's element kind: the
!> 3D tetrahedra (udar_element_driver) or the 2D triangles
!> (udar_tri_driver), chosen by the number of corners. The one place the
!> run loop meets the element kind; each call has the meaning documented
!> at the 3D driver's routine of the same name.
module udar_element_passes
  use udar_kinds, only: rk
  use udar_domain, only: domain_t
  use udar_fracture, only: erode_reasons
  use udar_element_driver, only: tet_volumes_pass => element_volumes, tet_update => element_update, &
      tet_forces_averaged => element_forces_averaged, tet_stiffness_bounds => element_stiffness_bounds, &
      tet_altitudes => element_altitudes, tet_current_volume => current_volume
  use udar_tri_driver, only: tri_element_volumes, tri_element_update, tri_element_forces_averaged, &
      tri_element_stiffness_bounds, tri_element_altitudes, tri_current_volume
  use udar_element_shared, only: nodal_pressures, nodal_reference_volumes, nodal_stable_dt, element_time_steps, &
      element_costs
  implicit none
  private
  public :: element_volumes, element_update, element_forces_averaged, element_stiffness_bounds, &
            element_altitudes, current_volume, nodal_pressures, nodal_reference_volumes, nodal_stable_dt, &
            element_time_steps, element_costs

contains

  subroutine element_volumes(dom)
    type(domain_t), intent(inout) :: dom
    if (dom%corners == 3) then
      call tri_element_volumes(dom)
    else
      call tet_volumes_pass(dom)
    end if
  end subroutine

  subroutine element_update(dom, dt, bad_elem, bad_j, n_eroded, eroded_any, dt_stable, dt_node)
    type(domain_t), intent(inout) :: dom
    real(rk), intent(in) :: dt
    integer, intent(out) :: bad_elem, bad_j, n_eroded(erode_reasons)
    logical, intent(out) :: eroded_any
    real(rk), intent(out) :: dt_stable
    integer, intent(out) :: dt_node
    if (dom%corners == 3) then
      call tri_element_update(dom, dt, bad_elem, bad_j, n_eroded, eroded_any, dt_stable, dt_node)
    else
      call tet_update(dom, dt, bad_elem, bad_j, n_eroded, eroded_any, dt_stable, dt_node)
    end if
  end subroutine

  subroutine element_forces_averaged(dom)
    type(domain_t), intent(inout) :: dom
    if (dom%corners == 3) then
      call tri_element_forces_averaged(dom)
    else
      call tet_forces_averaged(dom)
    end if
  end subroutine

  subroutine element_stiffness_bounds(dom)
    type(domain_t), intent(inout) :: dom
    if (dom%corners == 3) then
      call tri_element_stiffness_bounds(dom)
    else
      call tet_stiffness_bounds(dom)
    end if
  end subroutine

  subroutine element_altitudes(dom)
    type(domain_t), intent(inout) :: dom
    if (dom%corners == 3) then
      call tri_element_altitudes(dom)
    else
      call tet_altitudes(dom)
    end if
  end subroutine

  real(rk) function current_volume(dom, e) result(v)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: e
    if (dom%corners == 3) then
      v = tri_current_volume(dom, e)
    else
      v = tet_current_volume(dom, e)
    end if
  end function
end module udar_element_passes
