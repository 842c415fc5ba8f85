!> Unit tests of the 2D triangle kernels (udar_tri3, issue 14 item 2):
!> linear completeness, a rigid translation along the axis and a uniform
!> radial expansion exact, the forces the transpose of the strain rate (the
!> stress power exact), and a patch around an interior node in equilibrium
!> under a uniform stress with sigma_rr = sigma_hoop, axisymmetric and
!> plane strain.
program test_tri3
  use udar_kinds, only: rk
  use udar_strings, only: r2s
  use udar_tri3, only: tri_geometry, tri_smallest_altitude, tri_velocity_gradient, tri_internal_forces, tri_stiffness_bound
  use unit_checks, only: check, check_summary
  implicit none
  integer, parameter :: nfan = 7           ! triangles around the patch's interior node
  real(rk) :: x(1,3,2), v(1,3,2), grad(1,3,2), d(1,4), w(1), area(1), rbar(1), vol(1), f(1,3,2), s(1,4), p(1)
  real(rk) :: id(2,2), err, power, stress_power, h(1)
  integer :: k, m

  ! a skewed triangle off the axis, counter-clockwise
  x(1,:,1) = [0.3_rk, 1.1_rk, 0.6_rk]
  x(1,:,2) = [0.2_rk, 0.5_rk, 1.3_rk]
  call tri_geometry(1, 1, .true., x, area, rbar, vol, grad)
  call check('tri_area_by_hand', abs(area(1) - 0.5_rk*((1.1_rk - 0.3_rk)*(1.3_rk - 0.2_rk) - (0.6_rk - 0.3_rk)* &
             (0.5_rk - 0.2_rk))) < 1e-15_rk .and. abs(vol(1) - rbar(1)*area(1)) < 1e-15_rk .and. &
             abs(rbar(1) - 2.0_rk/3) < 1e-15_rk, 'A = '//r2s(area(1))//', rbar = '//r2s(rbar(1))//', V = rbar A per radian')
  ! linear completeness: sum_a x_a (x) grad N_a = I, sum_a grad N_a = 0
  do k = 1, 2
    do m = 1, 2
      id(k,m) = sum(x(1,:,k)*grad(1,:,m))
    end do
  end do
  err = maxval(abs(id - reshape([1.0_rk, 0.0_rk, 0.0_rk, 1.0_rk], [2, 2]))) + maxval(abs(sum(grad(1,:,:), dim=1)))
  call check('tri_linear_completeness', err < 1e-14_rk, 'error '//r2s(err))
  ! smallest altitude: the right triangle (0,0), (2,0), (0,1): 2 / sqrt(5) over the hypotenuse
  x(1,:,1) = [0.0_rk, 2.0_rk, 0.0_rk]
  x(1,:,2) = [0.0_rk, 0.0_rk, 1.0_rk]
  call tri_geometry(1, 1, .false., x, area, rbar, vol, grad)
  call tri_smallest_altitude(1, 1, grad, h)
  call check('tri_smallest_altitude_by_hand', abs(h(1) - 2.0_rk/sqrt(5.0_rk)) < 1e-15_rk, &
             'h = '//r2s(h(1))//' (2/sqrt 5 = '//r2s(2.0_rk/sqrt(5.0_rk))//')')
  x(1,:,1) = [0.3_rk, 1.1_rk, 0.6_rk]
  x(1,:,2) = [0.2_rk, 0.5_rk, 1.3_rk]
  call tri_geometry(1, 1, .true., x, area, rbar, vol, grad)

  ! rigid translation along the axis: no strain rate, no spin
  v(1,:,1) = 0.0_rk
  v(1,:,2) = 37.0_rk
  call tri_velocity_gradient(1, 1, .true., v, grad, rbar, d, w)
  call check('tri_rigid_axial_translation', maxval(abs(d)) + abs(w(1)) < 1e-13_rk, &
             'largest rate '//r2s(maxval(abs(d)))//' 1/s for v_z = 37 m/s')
  ! uniform radial and axial stretching v_r = a r, v_z = b z: d = (a, b, a, 0) exactly
  v(1,:,1) = 250.0_rk*x(1,:,1)
  v(1,:,2) = -80.0_rk*x(1,:,2)
  call tri_velocity_gradient(1, 1, .true., v, grad, rbar, d, w)
  err = maxval(abs(d(1,:) - [250.0_rk, -80.0_rk, 250.0_rk, 0.0_rk])) + abs(w(1))
  call check('tri_uniform_radial_expansion', err < 1e-12_rk, 'd_rr, d_zz, d_hoop, d_rz = '//r2s(d(1,1))//' '// &
             r2s(d(1,2))//' '//r2s(d(1,3))//' '//r2s(d(1,4))//' (250, -80, 250, 0)')
  ! plane strain: no hoop rate; a rigid rotation has no strain rate
  v(1,:,1) = -3.0_rk*x(1,:,2)
  v(1,:,2) = 3.0_rk*x(1,:,1)
  call tri_geometry(1, 1, .false., x, area, rbar, vol, grad)
  call tri_velocity_gradient(1, 1, .false., v, grad, rbar, d, w)
  call check('tri_plane_strain_rigid_rotation', maxval(abs(d)) < 1e-14_rk .and. abs(w(1) + 3.0_rk) < 1e-14_rk, &
             'd '//r2s(maxval(abs(d)))//', spin '//r2s(w(1))//' (-3)')

  ! the forces are the strain rate's transpose: sum_a f_a . v_a = -V sigma : d
  do k = 1, 2
    v(1,:,1) = [1.3_rk, -0.4_rk, 2.2_rk]
    v(1,:,2) = [0.7_rk, 1.9_rk, -1.1_rk]
    call tri_geometry(1, 1, k == 1, x, area, rbar, vol, grad)
    call tri_velocity_gradient(1, 1, k == 1, v, grad, rbar, d, w)
    s(1,:) = [2.0e8_rk, -1.5e8_rk, -0.5e8_rk, 0.7e8_rk]
    p(1) = 3.0e8_rk
    call tri_internal_forces(1, 1, k == 1, vol, area, grad, s, p, f)
    power = sum(f(1,:,:)*v(1,:,:))
    stress_power = -vol(1)*((s(1,1) - p(1))*d(1,1) + (s(1,2) - p(1))*d(1,2) + (s(1,3) - p(1))*d(1,3) &
                            + 2.0_rk*s(1,4)*d(1,4))
    call check('tri_force_work_is_stress_power_'//trim(merge('axisymmetric', 'plane_strain', k == 1)), &
               abs(power - stress_power) < 1e-14_rk*abs(stress_power), r2s(power)//' W against '//r2s(stress_power))
  end do

  call patch_equilibrium(.true.)
  call patch_equilibrium(.false.)
  ! the stiffness bound against the element's stiffness matrix, assembled
  ! column by column from the kernels: off the axis, with a corner on it,
  ! and in plane strain
  call stiffness_bound_holds('axisymmetric_off_axis', .true., [0.3_rk, 1.1_rk, 0.6_rk], [0.2_rk, 0.5_rk, 1.3_rk])
  call stiffness_bound_holds('axisymmetric_on_axis', .true., [0.0_rk, 0.4_rk, 0.1_rk], [0.0_rk, 0.1_rk, 0.5_rk])
  call stiffness_bound_holds('axisymmetric_edge_on_axis', .true., [0.0_rk, 0.1_rk, 0.0_rk], [0.0_rk, 0.05_rk, 0.1_rk])
  call stiffness_bound_holds('plane_strain', .false., [0.3_rk, 1.1_rk, 0.6_rk], [0.2_rk, 0.5_rk, 1.3_rk])
  call check_summary()

contains

  !> A fan of nfan triangles around an interior node (at r = 0.8, z = 0.1)
  !> under sigma_rr = sigma_hoop = -2e8, sigma_zz = 5e7, sigma_rz = 0
  !> (axisymmetric; plane strain also sigma_rz = 3e7): the interior node's
  !> summed force vanishes to round-off, a node on the rim's does not.
  subroutine patch_equilibrium(axisymmetric)
    logical, intent(in) :: axisymmetric
    real(rk) :: xf(nfan,3,2), gf(nfan,3,2), af(nfan), rf(nfan), vf(nfan), sf(nfan,4), pf(nfan), ff(nfan,3,2), &
                centre(2), rim(2,nfan), total(2), scale, angle, rim_force(2)
    integer :: e
    centre = [0.8_rk, 0.1_rk]
    do e = 1, nfan
      angle = 2.0_rk*acos(-1.0_rk)*(e - 1)/nfan + 0.1_rk*sin(3.0_rk*e)
      rim(:,e) = centre + (0.3_rk + 0.05_rk*cos(2.0_rk*e))*[cos(angle), sin(angle)]
    end do
    do e = 1, nfan
      xf(e,1,:) = centre
      xf(e,2,:) = rim(:,e)
      xf(e,3,:) = rim(:,mod(e, nfan) + 1)
    end do
    call tri_geometry(nfan, nfan, axisymmetric, xf, af, rf, vf, gf)
    sf(:,1) = 0.0_rk; sf(:,2) = 2.5e8_rk; sf(:,3) = 0.0_rk
    sf(:,4) = merge(0.0_rk, 3.0e7_rk, axisymmetric)
    pf = 2.0e8_rk
    call tri_internal_forces(nfan, nfan, axisymmetric, vf, af, gf, sf, pf, ff)
    total = sum(ff(:,1,:), dim=1)
    scale = 2.0e8_rk*sum(vf)/0.3_rk
    ! rim node 2 is corner 2 of triangle 2 and corner 3 of triangle 1
    rim_force = ff(2,2,:) + ff(1,3,:)
    call check('tri_patch_equilibrium_'//trim(merge('axisymmetric', 'plane_strain', axisymmetric)), &
               maxval(abs(total)) < 1e-13_rk*scale .and. maxval(abs(rim_force)) > 1e-3_rk*scale, &
               'interior node force '//r2s(maxval(abs(total)))//' N against a rim node''s '// &
               r2s(maxval(abs(rim_force)))//' N')
  end subroutine

  !> K(:,j) = -(forces of the elastic stress of the unit corner velocity j)
  !> (the forces are -K u), the radial rows and columns of corners on the
  !> axis taken out (their radial velocity is held at 0); its largest
  !> eigenvalue by power iteration (K is symmetric: the forces are the
  !> strain rate's transpose) must be at most the bound, and the bound
  !> within a factor 3 of it.
  subroutine stiffness_bound_holds(name, axisymmetric, r, z)
    character(len=*), intent(in) :: name
    logical, intent(in) :: axisymmetric
    real(rk), intent(in) :: r(3), z(3)
    real(rk), parameter :: bulk = 140.0e9_rk, shear = 45.0e9_rk
    real(rk) :: xe(1,3,2), ue(1,3,2), ge(1,3,2), de(1,4), we(1), ae(1), re(1), ve(1), se(1,4), pe(1), fe(1,3,2), &
                kmat(6,6), u(6), ku(6), lam_max, bound(1), asym
    integer :: j, it
    xe(1,:,1) = r
    xe(1,:,2) = z
    call tri_geometry(1, 1, axisymmetric, xe, ae, re, ve, ge)
    do j = 1, 6
      ue = 0.0_rk
      ue(1, mod(j - 1, 3) + 1, (j - 1)/3 + 1) = 1.0_rk
      call tri_velocity_gradient(1, 1, axisymmetric, ue, ge, re, de, we)
      pe(1) = -bulk*(de(1,1) + de(1,2) + de(1,3))
      se(1,1:3) = 2.0_rk*shear*(de(1,1:3) - (de(1,1) + de(1,2) + de(1,3))/3.0_rk)
      se(1,4) = 2.0_rk*shear*de(1,4)
      call tri_internal_forces(1, 1, axisymmetric, ve, ae, ge, se, pe, fe)
      kmat(:,j) = -[fe(1,:,1), fe(1,:,2)]
    end do
    asym = maxval(abs(kmat - transpose(kmat)))/maxval(abs(kmat))
    do j = 1, 3
      if (axisymmetric .and. r(j) == 0.0_rk) then
        kmat(j,:) = 0.0_rk
        kmat(:,j) = 0.0_rk
      end if
    end do
    u = [1.0_rk, 0.3_rk, -0.7_rk, 0.2_rk, 0.9_rk, -0.4_rk]
    do it = 1, 2000
      ku = matmul(kmat, u)
      u = ku/norm2(ku)
    end do
    lam_max = dot_product(u, matmul(kmat, u))
    call tri_stiffness_bound(1, 1, axisymmetric, ve, re, ge, [real(count(r > 0.0_rk), rk)], [bulk], shear, 1.0_rk, &
                             bound)
    call check('tri_stiffness_bound_'//name, asym < 1e-12_rk .and. bound(1) >= lam_max*(1.0_rk - 1e-12_rk) .and. &
               bound(1) <= 3.0_rk*lam_max, 'bound '//r2s(bound(1))//' N/m against the largest eigenvalue '// &
               r2s(lam_max)//' N/m (ratio '//r2s(bound(1)/lam_max)//'), K symmetric to '//r2s(asym))
  end subroutine
end program test_tri3
