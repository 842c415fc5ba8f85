!> How safe is the time step? The highest frequency of the assembled,
!> lumped-mass, linear-elastic tetrahedral mesh, by power iteration on
!> M^-1 K with the element kernels' own gradients and forces, against the
!> step the code takes: dt_safety (its default) times the nodal step
!> min_n 2 sqrt(m_n/k_n), k_n the sum of the incident elements' stiffness
!> bounds (tet_stiffness_bound with the formulation's volumetric share,
!> theory.md section 9). The critical step 2/omega_max must exceed it
!>  - on the undeformed OFHC Taylor bar (7316 tetrahedra) for Poisson's
!>    ratios from 0 to 0.45,
!>  - on the structured elastic bar (hexahedra split into tetrahedra, where
!>    min h/c overestimates the limit: 0.87 h/c at nu = 0), and
!>  - on two deformed meshes from real runs of the default element
!>    (tests/unit/meshes/*.txt: the Wilkins-Guinan bar at 80 us, with its
!>    thin foot lip, and the OFHC bar at 600 m/s at 25 us, a disc),
!> for the three formulations: plain, nodal-averaged (theory.md section 8,
!> linearised: J-bar from nodal volumes, the element pressures averaged
!> back to the nodes) and stabilised (linearised blend: (1-beta) of the
!> averaged volumetric strain plus beta of the element's own).
program test_stable_step
  use udar_kinds, only: rk
  use udar_strings, only: r2s
  use udar_gmsh, only: gmsh_mesh_t, gmsh_read
  use udar_config, only: run_cfg_t, numerics_cfg_t
  use udar_hydro, only: step_volumetric_share
  use udar_tet4, only: tet_gradients, tet_velocity_gradient, tet_internal_forces, tet_stiffness_bound
  use unit_checks, only: check, check_summary
  implicit none
  type(gmsh_mesh_t) :: mesh
  type(run_cfg_t) :: run_defaults
  type(numerics_cfg_t) :: numerics_defaults
  character(len=512) :: unit_dir
  character(len=:), allocatable :: msg
  logical :: ok
  integer :: n, ne
  integer, allocatable :: tet(:,:)
  real(rk), allocatable :: x0(:,:), x(:,:), grad(:,:,:), vol(:), h(:), rho(:), mass(:), u(:,:), ku(:,:), &
                           vol_node(:)
  real(rk) :: nus(4) = [0.0_rk, 0.3_rk, 0.35_rk, 0.45_rk]
  real(rk) :: beta
  integer :: k
  character(len=*), parameter :: form_name(3) = [character(len=10) :: 'plain', 'nodal', 'stabilised']

  call get_command_argument(1, unit_dir)
  ! the stiffest share the stabilised element takes (its share at a large
  ! departure from its nodes; the time step counts it everywhere)
  beta = numerics_defaults%stabilisation_large
  call read_undeformed(trim(unit_dir)//'/../regression/taylor_ofhc_baseline/taylor_ofhc_baseline.msh', 1.0e-3_rk)
  call prepare(8930.0_rk)
  do k = 1, size(nus)
    call all_formulations('ofhc_bar_undeformed', 124.0e9_rk, nus(k), 8930.0_rk)
  end do
  call read_undeformed(trim(unit_dir)//'/../regression/elastic_bar/elastic_bar.msh', 1.0_rk)
  call prepare(7850.0_rk)
  call all_formulations('elastic_bar_structured', 200.0e9_rk, 0.0_rk, 7850.0_rk)
  call read_frame(trim(unit_dir)//'/meshes/wg_80us.txt')
  call prepare(8930.0_rk)
  call all_formulations('wilkins_guinan_80us', 117.0e9_rk, 0.35_rk, 8930.0_rk)
  call read_frame(trim(unit_dir)//'/meshes/bar600_25us.txt')
  call prepare(8960.0_rk)
  call all_formulations('bar_600ms_25us', 128.8e9_rk, 0.35_rk, 8960.0_rk)
  call check_summary()

contains

  !> The three formulations on the current mesh, Young's modulus e_mod and
  !> Poisson's ratio nu.
  subroutine all_formulations(case_name, e_mod, nu, rho0)
    character(len=*), intent(in) :: case_name
    real(rk), intent(in) :: e_mod, nu, rho0
    real(rk) :: bulk, shear, c2(ne), dt_crit, dt_est, ratio, lam(ne), k_n(n), bulk_e(ne), g(ne,4,3), hc
    integer :: form, e
    bulk = e_mod/(3.0_rk*(1.0_rk - 2.0_rk*nu))
    shear = e_mod/(2.0_rk*(1.0_rk + nu))
    ! the code's element wave speed: bulk part at rho0 (linear EOS), shear part at the current density
    c2 = bulk/rho0 + 4.0_rk/3.0_rk*shear/rho
    hc = minval(h/sqrt(c2))
    ! the code's tangent bulk modulus rho c^2 - 4G/3 (linear EOS: K rho/rho0)
    bulk_e = rho*c2 - 4.0_rk/3.0_rk*shear
    g = grad
    do form = 1, 3
      dt_crit = 2.0_rk/sqrt(largest_eigenvalue(form, bulk, shear))
      call tet_stiffness_bound(ne, ne, vol, g, bulk_e, shear, &
                               step_volumetric_share(form /= 1, merge(beta, 0.0_rk, form == 3)), lam)
      k_n = 0
      do e = 1, ne
        k_n(tet(e,:)) = k_n(tet(e,:)) + lam(e)
      end do
      dt_est = 2.0_rk*sqrt(minval(mass/k_n))
      ratio = dt_crit/dt_est
      print '(a,a,a,a,a,f5.2,a,i0,a,i0,a,es11.4,a,es11.4,a,f6.3,a,f6.3,a,f6.3)', 'MEASURED ', case_name, ' ', &
        trim(form_name(form)), ' nu = ', nu, ' (', n, ' nodes, ', ne, ' tets): 2/omega_max = ', dt_crit, &
        ' s, nodal step = ', dt_est, ' s (', dt_est/hc, ' min h/c), ratio ', ratio, &
        ', margin at the default dt_safety ', ratio/run_defaults%dt_safety
      call check(case_name//'_'//trim(form_name(form))//'_default_step_below_the_assembled_limit_nu_'//r2s(nu), &
                 run_defaults%dt_safety < ratio, 'critical step '//r2s(ratio)//' times the estimate')
    end do
  end subroutine

  !> A gmsh mesh, undeformed: reference and current coordinates the same.
  subroutine read_undeformed(path, scale)
    character(len=*), intent(in) :: path
    real(rk), intent(in) :: scale
    call gmsh_read(path, scale, mesh, ok, msg)
    call check('mesh_read '//path, ok, msg)
    if (.not. ok) call check_summary()
    n = mesh%n_nodes
    ne = mesh%n_cells
    tet = mesh%cell
    x0 = mesh%x
    x = mesh%x
  end subroutine

  !> A deformed frame: reference and current coordinates, connectivity.
  subroutine read_frame(path)
    character(len=*), intent(in) :: path
    integer :: unit, i, ios
    open(newunit=unit, file=path, status='old', action='read', iostat=ios)
    call check('frame_read '//path, ios == 0, 'open')
    if (ios /= 0) call check_summary()
    read(unit, *) n, ne
    deallocate(x0, x, tet)
    allocate(x0(n,3), x(n,3), tet(ne,4))
    do i = 1, n
      read(unit, *) x0(i,:), x(i,:)
    end do
    do i = 1, ne
      read(unit, *) tet(i,:)
    end do
    close(unit)
  end subroutine

  !> Gradients, volumes and altitudes on the current coordinates; lumped
  !> masses from the reference volumes; element densities.
  subroutine prepare(rho0)
    real(rk), intent(in) :: rho0
    real(rk) :: xe(1,4,3), g(1,4,3), v(1), g2(1), v0(ne)
    integer :: e, a
    if (allocated(grad)) deallocate(grad, vol, h, rho, mass, u, ku, vol_node)
    allocate(grad(ne,4,3), vol(ne), h(ne), rho(ne), mass(n), u(3,n), ku(3,n), vol_node(n))
    do e = 1, ne
      do a = 1, 4
        xe(1,a,:) = x0(tet(e,a),:)
      end do
      call tet_gradients(1, 1, xe, v, g, g2)
      v0(e) = v(1)
      do a = 1, 4
        xe(1,a,:) = x(tet(e,a),:)
      end do
      call tet_gradients(1, 1, xe, v, g, g2)
      grad(e,:,:) = g(1,:,:)
      vol(e) = v(1)
      h(e) = 1.0_rk/sqrt(g2(1))
      rho(e) = rho0*v0(e)/vol(e)
    end do
    mass = 0
    vol_node = 0
    do e = 1, ne
      mass(tet(e,:)) = mass(tet(e,:)) + 0.25_rk*rho0*v0(e)
      vol_node(tet(e,:)) = vol_node(tet(e,:)) + 0.25_rk*vol(e)
    end do
  end subroutine

  !> K u for small strains about the current geometry: the element strain
  !> from the velocity-gradient kernel applied to u, sigma = K tr(eps) I +
  !> 2 G dev(eps) with the formulation's volumetric strain, and the element
  !> force kernel (which gives -K u).
  subroutine stiffness_times(form, bulk, shear, u, ku)
    integer, intent(in) :: form
    real(rk), intent(in) :: bulk, shear, u(:,:)
    real(rk), intent(out) :: ku(:,:)
    real(rk) :: ue(1,4,3), g(1,4,3), d(1,6), w(1,3), s(1,6), p(1), f(1,4,3)
    real(rk) :: strain(ne,6), tr(ne), j_node(n), p_node(n), w_avg, p_el(ne)
    integer :: a, e
    w_avg = merge(0.0_rk, merge(1.0_rk, 1.0_rk - beta, form == 2), form == 1)
    do e = 1, ne
      do a = 1, 4
        ue(1,a,:) = u(:,tet(e,a))
      end do
      g(1,:,:) = grad(e,:,:)
      call tet_velocity_gradient(1, 1, ue, g, d, w)
      strain(e,:) = d(1,:)
      tr(e) = d(1,1) + d(1,2) + d(1,3)
    end do
    if (w_avg > 0.0_rk) then
      ! delta V_a = 1/4 sum_e V_e tr(eps_e); J-bar_e = mean of dV_a/V_a; the
      ! element pressure -K J*_e, J*_e = w_avg J-bar_e + (1 - w_avg) tr(eps_e);
      ! its averaged share w_avg p_e goes to the nodes (volume-weighted), the
      ! element applies the mean of its nodes' plus its own share
      j_node = 0
      do e = 1, ne
        j_node(tet(e,:)) = j_node(tet(e,:)) + 0.25_rk*vol(e)*tr(e)
      end do
      j_node = j_node/vol_node
      p_node = 0
      do e = 1, ne
        p_el(e) = -bulk*(w_avg*0.25_rk*sum(j_node(tet(e,:))) + (1.0_rk - w_avg)*tr(e))
        p_node(tet(e,:)) = p_node(tet(e,:)) + 0.25_rk*vol(e)*w_avg*p_el(e)
      end do
      p_node = p_node/vol_node
    end if
    ku = 0
    do e = 1, ne
      g(1,:,:) = grad(e,:,:)
      s(1,1:3) = 2.0_rk*shear*(strain(e,1:3) - tr(e)/3.0_rk)
      s(1,4:6) = 2.0_rk*shear*strain(e,4:6)
      if (w_avg > 0.0_rk) then
        p(1) = 0.25_rk*sum(p_node(tet(e,:))) + (1.0_rk - w_avg)*p_el(e)
      else
        p(1) = -bulk*tr(e)
      end if
      call tet_internal_forces(1, 1, vol(e:e), g, s, p, f)
      do a = 1, 4
        ku(:,tet(e,a)) = ku(:,tet(e,a)) - f(1,a,:)
      end do
    end do
  end subroutine

  !> Power iteration on M^-1 K (symmetric in the M inner product); the
  !> Rayleigh quotient u.Ku / u.Mu approaches lambda_max from below.
  real(rk) function largest_eigenvalue(form, bulk, shear) result(lam)
    integer, intent(in) :: form
    real(rk), intent(in) :: bulk, shear
    integer :: it, i, j
    integer(8) :: seed
    real(rk) :: norm, lam_old
    seed = 12345
    do i = 1, n
      do j = 1, 3
        seed = mod(seed*1103515245_8 + 12345_8, 2147483648_8)
        u(j,i) = real(seed, rk)/2147483648.0_rk - 0.5_rk
      end do
    end do
    lam = 0
    do it = 1, 5000
      call stiffness_times(form, bulk, shear, u, ku)
      lam_old = lam
      lam = sum(u*ku)/sum(spread(mass, 1, 3)*u*u)
      do i = 1, n
        u(:,i) = ku(:,i)/mass(i)
      end do
      norm = sqrt(sum(spread(mass, 1, 3)*u*u))
      u = u/norm
      if (it > 50 .and. abs(lam - lam_old) < 1.0e-7_rk*lam) exit
    end do
  end function
end program test_stable_step
