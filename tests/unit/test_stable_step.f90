!> How safe is the time step? The highest frequency of the assembled,
!> lumped-mass, linear-elastic tetrahedral mesh of a real deck (the OFHC
!> Taylor bar, 7316 tetrahedra), by power iteration on M^-1 K with the
!> element kernels' own gradients and forces, against the element estimate
!> min_e h_e/c that the time step uses (theory.md §9). The critical step
!> 2/omega_max must exceed dt_safety (0.7) times the estimate, for
!> Poisson's ratios from 0 to 0.45: the margin the default relies on.
!> Both formulations: the plain element and the nodal-averaged one
!> (anti_locking, theory.md §8, linearised: J-bar from nodal volumes, the
!> element pressures averaged back to the nodes), whose volumetric part is
!> softer.
program test_stable_step
  use udar_kinds, only: rk
  use udar_strings, only: r2s
  use udar_gmsh, only: gmsh_mesh_t, gmsh_read
  use udar_tet4, only: tet_gradients, tet_velocity_gradient, tet_internal_forces
  use unit_checks, only: check, check_summary
  implicit none
  type(gmsh_mesh_t) :: mesh
  character(len=512) :: unit_dir
  character(len=:), allocatable :: msg
  logical :: ok
  real(rk), allocatable :: grad(:,:,:), vol(:), h(:), mass(:), u(:,:), ku(:,:), vol_node(:)
  real(rk), parameter :: rho = 8930.0_rk, e_mod = 124.0e9_rk, dt_safety = 0.7_rk
  real(rk) :: nus(4) = [0.0_rk, 0.3_rk, 0.35_rk, 0.45_rk]
  real(rk) :: bulk, shear, c, lam_max, dt_crit, dt_est, ratio
  integer :: n, ne, e, k, form
  logical :: nodal
  character(len=*), parameter :: form_name(2) = ['plain', 'nodal']

  call get_command_argument(1, unit_dir)
  call gmsh_read(trim(unit_dir)//'/../regression/taylor_ofhc_baseline/taylor_ofhc_baseline.msh', 1.0e-3_rk, &
                 mesh, ok, msg)
  call check('mesh_read', ok, msg)
  if (.not. ok) call check_summary()
  n = mesh%n_nodes
  ne = mesh%n_tets
  allocate(grad(ne,4,3), vol(ne), h(ne), mass(n), u(3,n), ku(3,n), vol_node(n))
  call geometry()
  mass = 0
  vol_node = 0
  do e = 1, ne
    mass(mesh%tet(e,:)) = mass(mesh%tet(e,:)) + 0.25_rk*rho*vol(e)
    vol_node(mesh%tet(e,:)) = vol_node(mesh%tet(e,:)) + 0.25_rk*vol(e)
  end do
  do form = 1, 2
  nodal = form == 2
  do k = 1, size(nus)
    bulk = e_mod/(3.0_rk*(1.0_rk - 2.0_rk*nus(k)))
    shear = e_mod/(2.0_rk*(1.0_rk + nus(k)))
    c = sqrt((bulk + 4.0_rk/3.0_rk*shear)/rho)
    lam_max = largest_eigenvalue(bulk, shear)
    dt_crit = 2.0_rk/sqrt(lam_max)
    dt_est = minval(h)/c
    ratio = dt_crit/dt_est
    print '(a,a,a,f5.2,a,i0,a,i0,a,es11.4,a,es11.4,a,f6.3)', 'MEASURED ', form_name(form), ' nu = ', nus(k), &
      ' (', n, ' nodes, ', ne, ' tets): 2/omega_max = ', dt_crit, ' s, min h/c = ', dt_est, ' s, ratio ', ratio
    call check(form_name(form)//'_dt_safety_0.7_below_the_assembled_limit_nu_'//r2s(nus(k)), dt_safety < ratio, &
               'critical step '//r2s(ratio)//' h/c')
  end do
  end do
  call check_summary()

contains

  subroutine geometry()
    real(rk) :: x(1,4,3), g(1,4,3), v(1), g2(1)
    integer :: a
    do e = 1, ne
      do a = 1, 4
        x(1,a,:) = mesh%x(mesh%tet(e,a),:)
      end do
      call tet_gradients(1, 1, x, v, g, g2)
      grad(e,:,:) = g(1,:,:)
      vol(e) = v(1)
      h(e) = 1.0_rk/sqrt(g2(1))
    end do
  end subroutine

  !> K u for small strains: the element strain from the velocity-gradient
  !> kernel applied to u, sigma = K tr(eps) I + 2 G dev(eps), and the
  !> element force kernel (which gives -K u).
  subroutine stiffness_times(bulk, shear, u, ku)
    real(rk), intent(in) :: bulk, shear, u(:,:)
    real(rk), intent(out) :: ku(:,:)
    real(rk) :: ue(1,4,3), g(1,4,3), d(1,6), w(1,3), s(1,6), p(1), f(1,4,3)
    real(rk) :: strain(ne,6), tr(ne), j_node(n), p_node(n)
    integer :: a
    do e = 1, ne
      do a = 1, 4
        ue(1,a,:) = u(:,mesh%tet(e,a))
      end do
      g(1,:,:) = grad(e,:,:)
      call tet_velocity_gradient(1, 1, ue, g, d, w)
      strain(e,:) = d(1,:)
      tr(e) = d(1,1) + d(1,2) + d(1,3)
    end do
    if (nodal) then
      ! delta V_a = 1/4 sum_e V_e tr(eps_e); J-bar_e = mean of dV_a/V_a; p_e = -K J-bar_e;
      ! P_a = volume-weighted mean of p_e; the element applies the mean of its P_a
      j_node = 0
      do e = 1, ne
        j_node(mesh%tet(e,:)) = j_node(mesh%tet(e,:)) + 0.25_rk*vol(e)*tr(e)
      end do
      j_node = j_node/vol_node
      p_node = 0
      do e = 1, ne
        p_node(mesh%tet(e,:)) = p_node(mesh%tet(e,:)) - 0.25_rk*vol(e)*bulk*0.25_rk*sum(j_node(mesh%tet(e,:)))
      end do
      p_node = p_node/vol_node
    end if
    ku = 0
    do e = 1, ne
      g(1,:,:) = grad(e,:,:)
      s(1,1:3) = 2.0_rk*shear*(strain(e,1:3) - tr(e)/3.0_rk)
      s(1,4:6) = 2.0_rk*shear*strain(e,4:6)
      p(1) = -bulk*tr(e)
      if (nodal) p(1) = 0.25_rk*sum(p_node(mesh%tet(e,:)))
      call tet_internal_forces(1, 1, vol(e:e), g, s, p, f)
      do a = 1, 4
        ku(:,mesh%tet(e,a)) = ku(:,mesh%tet(e,a)) - f(1,a,:)
      end do
    end do
  end subroutine

  !> Power iteration on M^-1 K (symmetric in the M inner product); the
  !> Rayleigh quotient u.Ku / u.Mu approaches lambda_max from below.
  real(rk) function largest_eigenvalue(bulk, shear) result(lam)
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
    do it = 1, 3000
      call stiffness_times(bulk, shear, u, ku)
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
