!> How safe is the 2D time step? test_stable_step's measurement for the
!> three-node triangle (theory.md sections 9 and 14): the highest
!> frequency of the assembled, lumped-mass, linear-elastic triangle mesh,
!> axisymmetric (per radian: masses and stiffness alike, so the ratio is
!> that of the full revolution) or plane strain, by power iteration on
!> M^-1 K with the tri3 kernels' own strain rate and forces (the whole mesh
!> as one block), against the nodal step min_n 2 sqrt(m_n/k_n), k_n the sum
!> of the incident elements' tri_stiffness_bound. Axisymmetric, the nodes on
!> r = 0 keep u_r = 0 (the axis condition: those components are held at 0 in
!> the iteration, and the bound counts the corners off the axis). The
!> formulations are linearised as in 3D: plain, nodal-averaged (J-bar the
!> mean of the corners' dV_a/V_a, V_a a third of the incident volumes; the
!> element pressures averaged back to the nodes) and stabilised ((1-beta)
!> of the averaged volumetric strain plus beta of the element's own). Each
!> ratio 2/omega_max over the nodal step is measured with the whole
!> volumetric part in the bound (phi = 1, a bound of the plain element's
!> stiffness) and with the triangle's patch share (step_volumetric_share
!> with tri_patch_share = 1/4: the step the driver takes); the default
!> dt_safety must be below both ratios on
!>  - the undeformed Wilkins-Guinan mesh (regression/taylor_wg_2d, h =
!>    0.2 mm), axisymmetric and read as plane strain, nu from 0 to 0.49,
!>  - the structured axisymmetric elastic bar (regression/elastic_bar_2d,
!>    right triangles), nu = 0 and 0.49, and
!>  - a deformed frame (tests/unit/meshes/wg2d_80us.txt: bin/udar 0.5.10,
!>    at 5ea6953, on the taylor_wg_2d deck with its mesh made at h = 0.4 mm,
!>    gmsh -setnumber h 0.4, default element 'stabilised', the field step
!>    at 80 us, cycle 31,061; element areas down to 0.13 of their
!>    reference), nu = 0.35.
!> Measured: 1.16 at the least with the patch share. The tetrahedron's 1/6
!> would do up to nu = 0.45 (1.16 at the least) but towards nu = 0.5 (G/K
!> -> 0, a material without strength) it leaves the 'nodal' triangle at
!> 0.93 on the structured bar and the plane-strain mesh (nu up to 0.49999,
!> not kept: 2 minutes in the debug build), no margin over dt_safety 0.9;
!> with 1/4 the bound scales by sqrt(3/2) there.
program test_stable_step_2d
  use udar_kinds, only: rk
  use udar_strings, only: r2s
  use udar_gmsh, only: gmsh_mesh_t, gmsh_read
  use udar_config, only: run_cfg_t, numerics_cfg_t
  use udar_hydro, only: step_volumetric_share
  use udar_tri3, only: tri_geometry, tri_smallest_altitude, tri_velocity_gradient, tri_internal_forces, &
      tri_stiffness_bound, tri_patch_share
  use unit_checks, only: check, check_summary
  implicit none
  type(run_cfg_t) :: run_defaults
  type(numerics_cfg_t) :: numerics_defaults
  character(len=512) :: unit_dir
  character(len=:), allocatable :: wg
  logical :: axi
  integer :: n, ne, k
  integer, allocatable :: tri(:,:)
  ! the mesh: reference and current (r, z); on the current geometry the
  ! elements' area, mean radius, volume (per radian), gradients, smallest
  ! altitude, reference over current volume and corners off the axis; the
  ! nodes' reference and current volumes (a third of each incident
  ! element's) and free components (0 for u_r on the axis)
  real(rk), allocatable :: x0(:,:), x(:,:), area(:), rbar(:), vol(:), grad(:,:,:), h(:), v0_v(:), free_r(:), &
                           vol0_node(:), vol_node(:), free(:,:)
  real(rk) :: nus(5) = [0.0_rk, 0.3_rk, 0.35_rk, 0.45_rk, 0.49_rk]
  real(rk) :: beta
  character(len=*), parameter :: form_name(3) = [character(len=10) :: 'plain', 'nodal', 'stabilised']

  call get_command_argument(1, unit_dir)
  beta = numerics_defaults%stabilisation_large
  wg = trim(unit_dir)//'/../regression/taylor_wg_2d/taylor_wg_2d.msh'
  call read_mesh(wg, 1.0e-3_rk, .true.)
  do k = 1, size(nus)
    call all_formulations('wg2d_axisymmetric_undeformed', 117.0e9_rk, nus(k), 8930.0_rk)
  end do
  call read_mesh(trim(unit_dir)//'/../regression/elastic_bar_2d/elastic_bar_2d.msh', 1.0_rk, .true.)
  call all_formulations('elastic_bar_2d_structured', 200.0e9_rk, 0.0_rk, 7850.0_rk)
  call all_formulations('elastic_bar_2d_structured', 200.0e9_rk, 0.49_rk, 7850.0_rk)
  call read_mesh(wg, 1.0e-3_rk, .false.)
  do k = 1, size(nus)
    call all_formulations('wg2d_plane_strain_undeformed', 117.0e9_rk, nus(k), 8930.0_rk)
  end do
  call read_frame(trim(unit_dir)//'/meshes/wg2d_80us.txt')
  call all_formulations('wg2d_axisymmetric_80us', 117.0e9_rk, 0.35_rk, 8930.0_rk)
  call check_summary()

contains

  !> The three formulations on the current mesh, Young's modulus e_mod,
  !> Poisson's ratio nu and reference density rho0: the assembled limit
  !> against the nodal step with phi = 1 (checked) and with the patch share.
  subroutine all_formulations(case_name, e_mod, nu, rho0)
    character(len=*), intent(in) :: case_name
    real(rk), intent(in) :: e_mod, nu, rho0
    real(rk) :: bulk, shear, rho(ne), mass(n), c2(ne), bulk_e(ne), hc, dt_crit, dt_one, dt_patch, phi
    integer :: form, iterations
    bulk = e_mod/(3.0_rk*(1.0_rk - 2.0_rk*nu))
    shear = e_mod/(2.0_rk*(1.0_rk + nu))
    rho = rho0*v0_v
    mass = rho0*vol0_node
    ! the code's wave speed (linear EOS: bulk part at rho0, shear part at the
    ! current density) and tangent bulk modulus rho c^2 - 4G/3 = K rho/rho0,
    ! in the bound and in the assembled stiffness alike
    c2 = bulk/rho0 + 4.0_rk/3.0_rk*shear/rho
    bulk_e = rho*c2 - 4.0_rk/3.0_rk*shear
    hc = minval(h/sqrt(c2))
    do form = 1, 3
      dt_crit = 2.0_rk/sqrt(largest_eigenvalue(form, mass, bulk_e, shear, iterations))
      dt_one = nodal_step(mass, bulk_e, shear, 1.0_rk)
      phi = step_volumetric_share(form /= 1, merge(beta, 0.0_rk, form == 3), tri_patch_share)
      dt_patch = nodal_step(mass, bulk_e, shear, phi)
      print '(a,a,a,a,a,f5.2,a,i0,a,i0,a,es11.4,a,i0,a,es11.4,a,f6.3,a,f6.3,a,f5.3,a,f6.3)', 'MEASURED ', case_name, &
        ' ', trim(form_name(form)), ' nu = ', nu, ' (', n, ' nodes, ', ne, ' triangles): 2/omega_max = ', dt_crit, &
        ' s (', iterations, ' iterations), nodal step (phi = 1) = ', dt_one, ' s (', dt_one/hc, &
        ' min h/c), ratio ', dt_crit/dt_one, '; patch share phi = ', phi, ': ratio ', dt_crit/dt_patch
      call check(case_name//'_'//trim(form_name(form))//'_default_step_below_the_assembled_limit_nu_'//r2s(nu), &
                 run_defaults%dt_safety < dt_crit/dt_one, 'critical step '//r2s(dt_crit/dt_one)//' times the estimate')
      ! the step the driver takes: the triangle's patch share
      call check(case_name//'_'//trim(form_name(form))//'_patch_share_step_below_the_assembled_limit_nu_'//r2s(nu), &
                 run_defaults%dt_safety < dt_crit/dt_patch, 'critical step '//r2s(dt_crit/dt_patch)// &
                 ' times the estimate with phi = '//r2s(phi))
    end do
  end subroutine

  !> The nodal step 2 min_n sqrt(m_n/k_n) of the bounds with share phi.
  real(rk) function nodal_step(mass, bulk_e, shear, phi) result(dt)
    real(rk), intent(in) :: mass(n), bulk_e(ne), shear, phi
    real(rk) :: lam(ne), k_n(n)
    integer :: e
    call tri_stiffness_bound(ne, ne, axi, vol, rbar, grad, free_r, bulk_e, shear, phi, lam)
    k_n = 0
    do e = 1, ne
      k_n(tri(e,:)) = k_n(tri(e,:)) + lam(e)
    end do
    dt = 2.0_rk*sqrt(minval(mass/k_n))
  end function

  !> A gmsh mesh, undeformed, axisymmetric or plane strain (the set-up's
  !> rule: |r| within 1e-12 of the mesh's size is on the axis).
  subroutine read_mesh(path, scale, axisymmetric)
    character(len=*), intent(in) :: path
    real(rk), intent(in) :: scale
    logical, intent(in) :: axisymmetric
    type(gmsh_mesh_t) :: mesh
    character(len=:), allocatable :: msg
    logical :: ok
    call gmsh_read(path, scale, mesh, ok, msg, dim=2)
    call check('mesh_read '//path, ok, msg)
    if (.not. ok) call check_summary()
    if (axisymmetric) where (abs(mesh%x(:,1)) <= 1.0e-12_rk*maxval(abs(mesh%x))) mesh%x(:,1) = 0.0_rk
    n = mesh%n_nodes
    ne = mesh%n_cells
    tri = mesh%cell
    x0 = mesh%x(:,1:2)
    x = x0
    call prepare(path, axisymmetric)
  end subroutine

  !> A deformed axisymmetric frame: n ne, then per node the reference and
  !> current coordinates (r, z, 0), per element its corners (1-based).
  subroutine read_frame(path)
    character(len=*), intent(in) :: path
    real(rk) :: row(6)
    integer :: unit, i, ios
    open(newunit=unit, file=path, status='old', action='read', iostat=ios)
    call check('frame_read '//path, ios == 0, 'open')
    if (ios /= 0) call check_summary()
    read(unit, *) n, ne
    if (allocated(tri)) deallocate(x0, x, tri)
    allocate(x0(n,2), x(n,2), tri(ne,3))
    do i = 1, n
      read(unit, *) row
      x0(i,:) = row(1:2)
      x(i,:) = row(4:5)
    end do
    do i = 1, ne
      read(unit, *) tri(i,:)
    end do
    close(unit)
    call prepare(path, .true.)
  end subroutine

  !> Geometry of the mesh read from path on the current coordinates, the
  !> ratio V0/V (rho over rho0), the nodal volumes and the axis condition.
  subroutine prepare(path, axisymmetric)
    character(len=*), intent(in) :: path
    logical, intent(in) :: axisymmetric
    real(rk) :: xe(ne,3,2), a0(ne), r0(ne), v0(ne)
    integer :: e, a
    axi = axisymmetric
    if (allocated(area)) deallocate(area, rbar, vol, grad, h, v0_v, free_r, vol0_node, vol_node, free)
    allocate(area(ne), rbar(ne), vol(ne), grad(ne,3,2), h(ne), v0_v(ne), free_r(ne), vol0_node(n), vol_node(n), &
             free(2,n))
    do a = 1, 3
      xe(:,a,:) = x0(tri(:,a),:)
    end do
    call tri_geometry(ne, ne, axi, xe, a0, r0, v0, grad)
    do a = 1, 3
      xe(:,a,:) = x(tri(:,a),:)
    end do
    call tri_geometry(ne, ne, axi, xe, area, rbar, vol, grad)
    call tri_smallest_altitude(ne, ne, grad, h)
    call check('positive_areas '//path, minval(area) > 0.0_rk .and. minval(a0) > 0.0_rk, &
               'smallest area '//r2s(minval(area))//' m^2')
    v0_v = v0/vol
    ! the axis condition: u_r = 0 on r = 0 (axisymmetric only)
    free = 1.0_rk
    if (axi) where (x(:,1) == 0.0_rk) free(1,:) = 0.0_rk
    free_r = free(1,tri(:,1)) + free(1,tri(:,2)) + free(1,tri(:,3))
    vol0_node = 0
    vol_node = 0
    do e = 1, ne
      vol0_node(tri(e,:)) = vol0_node(tri(e,:)) + v0(e)/3.0_rk
      vol_node(tri(e,:)) = vol_node(tri(e,:)) + vol(e)/3.0_rk
    end do
  end subroutine

  !> K u for small displacements u(2,n) about the current geometry: the
  !> strain from the strain-rate kernel, sigma = bulk_e tr(eps) I + 2 G
  !> dev(eps) with the formulation's volumetric strain, the force kernel
  !> (which gives -K u), the axis components held at 0.
  subroutine stiffness_times(form, bulk_e, shear, u, ku)
    integer, intent(in) :: form
    real(rk), intent(in) :: bulk_e(ne), shear, u(2,n)
    real(rk), intent(out) :: ku(2,n)
    real(rk) :: ue(ne,3,2), d(ne,4), w(ne), s(ne,4), p(ne), f(ne,3,2), tr(ne), p_el(ne), j_node(n), p_node(n), w_avg
    integer :: a, e
    w_avg = merge(0.0_rk, merge(1.0_rk, 1.0_rk - beta, form == 2), form == 1)
    do a = 1, 3
      ue(:,a,1) = u(1,tri(:,a))
      ue(:,a,2) = u(2,tri(:,a))
    end do
    call tri_velocity_gradient(ne, ne, axi, ue, grad, rbar, d, w)
    tr = d(:,1) + d(:,2) + d(:,3)
    p = -bulk_e*tr
    if (w_avg > 0.0_rk) then
      ! dV_a = 1/3 sum_e V_e tr(eps_e); J-bar_e the mean of dV_a/V_a over its
      ! corners; the element pressure -K J*_e, J*_e = w_avg J-bar_e + (1 -
      ! w_avg) tr(eps_e); its averaged share w_avg p_e goes to the nodes
      ! (volume-weighted), the element applies their mean plus its own share
      j_node = 0
      do e = 1, ne
        j_node(tri(e,:)) = j_node(tri(e,:)) + vol(e)*tr(e)/3.0_rk
      end do
      j_node = j_node/vol_node
      p_el = -bulk_e*(w_avg*corner_mean(j_node) + (1.0_rk - w_avg)*tr)
      p_node = 0
      do e = 1, ne
        p_node(tri(e,:)) = p_node(tri(e,:)) + vol(e)*w_avg*p_el(e)/3.0_rk
      end do
      p = corner_mean(p_node/vol_node) + (1.0_rk - w_avg)*p_el
    end if
    do a = 1, 3
      s(:,a) = 2.0_rk*shear*(d(:,a) - tr/3.0_rk)
    end do
    s(:,4) = 2.0_rk*shear*d(:,4)
    call tri_internal_forces(ne, ne, axi, vol, area, grad, s, p, f)
    ku = 0
    do e = 1, ne
      do a = 1, 3
        ku(:,tri(e,a)) = ku(:,tri(e,a)) - f(e,a,:)
      end do
    end do
    ku = free*ku
  end subroutine

  !> The mean of a nodal quantity over each element's corners.
  function corner_mean(q) result(qe)
    real(rk), intent(in) :: q(n)
    real(rk) :: qe(ne)
    qe = (q(tri(:,1)) + q(tri(:,2)) + q(tri(:,3)))/3.0_rk
  end function

  !> Power iteration on M^-1 K (symmetric in the M inner product) in the
  !> free components; the Rayleigh quotient u.Ku / u.Mu approaches
  !> lambda_max from below: iterated until it changes by less than 1e-9
  !> of itself.
  real(rk) function largest_eigenvalue(form, mass, bulk_e, shear, iterations) result(lam)
    integer, intent(in) :: form
    real(rk), intent(in) :: mass(n), bulk_e(ne), shear
    integer, intent(out) :: iterations
    real(rk) :: u(2,n), ku(2,n), m2(2,n), lam_old
    integer :: i, j
    integer(8) :: seed
    seed = 12345
    do i = 1, n
      do j = 1, 2
        seed = mod(seed*1103515245_8 + 12345_8, 2147483648_8)
        u(j,i) = free(j,i)*(real(seed, rk)/2147483648.0_rk - 0.5_rk)
      end do
    end do
    m2 = spread(mass, 1, 2)
    lam = 0
    do iterations = 1, 20000
      call stiffness_times(form, bulk_e, shear, u, ku)
      lam_old = lam
      lam = sum(u*ku)/sum(m2*u*u)
      u = ku/m2
      u = u/sqrt(sum(m2*u*u))
      if (iterations > 50 .and. abs(lam - lam_old) < 1.0e-9_rk*lam) exit
    end do
    iterations = min(iterations, 20000)
  end function
end program test_stable_step_2d
