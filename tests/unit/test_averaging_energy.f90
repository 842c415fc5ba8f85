!> The energy identity behind the nodal-averaged element (theory.md section
!> 8): for any element pressures p_e and any motion of the nodes,
!>   sum_e V0_e p_e dJbar_e = sum_f pbar_f dV_f   (alive elements),
!> Jbar_e the mean of its nodes' J_a = V_a / Vref_a, pbar_f the mean of its
!> nodes' pressures P_a (nodal_pressures), dV_f its volume change. The
!> identity makes the averaged forces do exactly the work the elements book,
!> and it must survive erosion: after elements are eroded and the nodes that
!> lost one have Vref_a rebased (nodal_reference_volumes), P_a must be taken
!> against Vref_a, not against the nodal reference volume V0_a. Checked on the
!> elastic-bar mesh (4800 tetrahedra), deformed, before and after eroding
!> elements, to round-off.
program test_averaging_energy
  use udar_kinds, only: rk, max_path_len
  use udar_comms, only: comms_init, comms_finalize
  use udar_config, only: config_t
  use udar_domain, only: domain_t
  use udar_setup, only: init_state
  use udar_distribution, only: distribute_domain
  use udar_comms, only: halo_t
  use udar_fracture, only: el_eroded
  use udar_element_driver, only: element_volumes, current_volume
  use udar_element_shared, only: nodal_reference_volumes, nodal_pressures
  use udar_strings, only: r2s, itoa
  use unit_checks, only: check, check_summary
  use unit_domains, only: elastic_bar_mesh_domain
  implicit none
  type(config_t) :: cfg
  type(domain_t) :: glob, dom
  type(halo_t) :: halo
  character(len=max_path_len) :: unit_dir
  integer, allocatable :: part(:)
  integer :: e, n_eroded
  real(rk) :: lhs, rhs, scale

  call comms_init()
  call get_command_argument(1, unit_dir)
  call elastic_bar_mesh_domain(trim(unit_dir), cfg, glob)
  allocate(part(glob%n_elems), source=0)
  call distribute_domain(glob, part, 0, dom, halo)
  call init_state(dom)
  dom%stab_beta = 0.0_rk         ! nodal_pressures averages el_p itself
  dom%stab_beta_large = 0.0_rk

  ! a deformed state: every node moved by up to 2 % of the bar's width
  call move_nodes(0.02_rk, 1)
  call identity('undeformed_reference_volumes')

  ! erode every 37th element at the deformed state and rebase, as a run does
  call element_volumes(dom)
  call store_element_volumes()
  n_eroded = 0
  do e = 1, dom%n_elems, 37
    dom%el_state(e) = el_eroded
    n_eroded = n_eroded + 1
  end do
  call nodal_reference_volumes(dom, rebase=.true.)
  call check('rebase_changed_reference_volumes', any(dom%nd_vref(1:dom%n_owned_nodes) /= &
             dom%nd_vol0(1:dom%n_owned_nodes)), itoa(n_eroded)//' elements eroded')
  call move_nodes(0.01_rk, 2)
  call identity('after_erosion_and_rebase')
  call comms_finalize()
  call check_summary()

contains

  !> Nodes moved from their current place by a fixed pseudo-random field of
  !> amplitude frac times the bar's smallest extent.
  subroutine move_nodes(frac, seed)
    real(rk), intent(in) :: frac
    integer, intent(in) :: seed
    real(rk) :: width
    integer :: n
    width = minval(maxval(dom%nd_x0, dim=2) - minval(dom%nd_x0, dim=2))
    do n = 1, dom%n_nodes
      dom%nd_x(:,n) = dom%nd_x(:,n) + frac*width*[sin(1.7_rk*n + seed), cos(2.3_rk*n*seed), sin(0.9_rk*n - seed)]
    end do
  end subroutine

  !> el_vol from the current coordinates (as element_update keeps it).
  subroutine store_element_volumes()
    integer :: f
    do f = 1, dom%n_elems
      dom%el_vol(f) = current_volume(dom, f)
    end do
  end subroutine

  !> Pressures p_e on the alive elements, P_a from nodal_pressures, then a
  !> further motion: the volumetric work both ways.
  subroutine identity(name)
    character(len=*), intent(in) :: name
    real(rk), allocatable :: jbar0(:), vol0(:)
    real(rk) :: pbar
    integer :: f
    do f = 1, dom%n_elems
      dom%el_p(f) = 1.0e9_rk*(1.0_rk + 0.5_rk*sin(0.37_rk*f))
    end do
    call nodal_pressures(dom)
    call element_volumes(dom)
    call store_element_volumes()
    jbar0 = element_jbar()
    vol0 = dom%el_vol
    call move_nodes(0.001_rk, 3)
    call element_volumes(dom)
    call store_element_volumes()
    lhs = 0.0_rk
    rhs = 0.0_rk
    scale = 0.0_rk
    associate (jbar1 => element_jbar())
      do f = 1, dom%n_elems
        if (dom%el_state(f) == el_eroded) cycle
        pbar = 0.25_rk*sum(dom%nd_p(dom%el_conn(f,:)))
        lhs = lhs + dom%el_vol0(f)*dom%el_p(f)*(jbar1(f) - jbar0(f))
        rhs = rhs + pbar*(dom%el_vol(f) - vol0(f))
        scale = scale + abs(pbar*(dom%el_vol(f) - vol0(f)))
      end do
    end associate
    call check('volumetric_work_identity_'//name, abs(lhs - rhs) <= 1.0e-10_rk*scale, &
               'sum V0 p dJbar = '//r2s(lhs)//' J, sum pbar dV = '//r2s(rhs)//' J (sum of |terms| '//r2s(scale)//' J)')
  end subroutine

  !> The element means of the nodal volume ratios.
  function element_jbar() result(jb)
    real(rk), allocatable :: jb(:)
    integer :: f
    allocate(jb(dom%n_elems))
    do f = 1, dom%n_elems
      jb(f) = 0.25_rk*sum(dom%nd_j(dom%el_conn(f,:)))
    end do
  end function
end program test_averaging_energy
