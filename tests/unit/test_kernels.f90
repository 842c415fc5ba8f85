!> Unit tests of the pure kernels: tet4 geometry, objectivity of the stress
!> update, radial return, equations of state against hand-computed values.
program test_kernels
  use udar_kinds, only: rk
  use udar_strings, only: r2s, itoa
  use udar_config, only: material_cfg_t, strength_perfectly_plastic, strength_linear_hardening, &
      strength_johnson_cook, strength_elastic, jc_rate_plastic, jc_rate_total
  use udar_tet4, only: tet_volume, tet_gradients, tet_velocity_gradient
  use udar_strength, only: strength_block, von_mises, yield_stress, thermal_softening, power_ratio
  use udar_eos, only: eos_linear_ab, eos_mie_gruneisen_ab
  use udar_hydro, only: volumetric_update, blended_volume_ratio, blended_volume_ratios, blended_pressures, blend_exponent
  use udar_fracture, only: fracture_update, jc_fracture_strain
  use udar_config, only: fracture_plastic_strain, fracture_johnson_cook
  use unit_checks, only: check, check_summary
  implicit none
  real(rk) :: w_test(3) = 0.0_rk   ! spin seen by one_step

  call test_tet_geometry()
  call test_rigid_rotation()
  call test_radial_return()
  call test_block_returns()
  call test_eos()
  call test_fracture()
  call test_blend()
  call check_summary()

contains


  subroutine test_tet_geometry()
    real(rk) :: x(1,4,3), vol(1), grad(1,4,3), h(1), xr(4,3), id(3,3), err
    integer :: a, k, m
    ! unit right tetrahedron
    x(1,1,:) = [0, 0, 0]; x(1,2,:) = [1, 0, 0]; x(1,3,:) = [0, 1, 0]; x(1,4,:) = [0, 0, 1]
    call tet_gradients(1, 1, x, vol, grad, h)
    h = 1/sqrt(h)
    call check('tet_volume_unit', abs(vol(1) - 1.0_rk/6) < 1e-15_rk, 'V = '//r2s(vol(1))//' (1/6)')
    call check('tet_gradient_unit', maxval(abs(grad(1,1,:) + 1)) < 1e-15_rk .and. &
               abs(grad(1,2,1) - 1) < 1e-15_rk .and. abs(grad(1,4,3) - 1) < 1e-15_rk, 'grad N1 = (-1,-1,-1), grad N2 = e_x')
    call check('tet_min_altitude', abs(h(1) - 1.0_rk/sqrt(3.0_rk)) < 1e-14_rk, 'h = '//r2s(h(1))//' (1/sqrt 3)')
    ! a skewed tetrahedron: partition of unity and linear completeness sum_a x_a (x) grad N_a = I
    x(1,1,:) = [0.1_rk, -0.2_rk, 0.3_rk]; x(1,2,:) = [1.3_rk, 0.1_rk, -0.2_rk]
    x(1,3,:) = [0.2_rk, 0.9_rk, 0.4_rk]; x(1,4,:) = [0.3_rk, 0.2_rk, 1.7_rk]
    call tet_gradients(1, 1, x, vol, grad, h)
    xr = x(1,:,:)
    call check('tet_volume_skew', abs(vol(1) - tet_volume(xr)) < 1e-15_rk .and. vol(1) > 0, 'block and scalar volume agree')
    err = 0
    do k = 1, 3
      do m = 1, 3
        id(k,m) = sum([(x(1,a,k)*grad(1,a,m), a = 1, 4)])
        err = max(err, abs(id(k,m) - merge(1.0_rk, 0.0_rk, k == m)))
      end do
      err = max(err, abs(sum(grad(1,:,k))))
    end do
    call check('tet_gradient_completeness', err < 1e-14_rk, 'max error '//r2s(err))
  end subroutine

  !> Rigid rotation v = omega x x: zero strain rate, and the stress rotated
  !> by the Jaumann update keeps its invariants.
  subroutine test_rigid_rotation()
    real(rk) :: x(1,4,3), v(1,4,3), vol(1), grad(1,4,3), h(1), d(1,6), w(1,3), omega(3), s(6), s0(6)
    real(rk) :: i2_0, i3_0, dt, xa(3), eps, de, wd, wp
    type(material_cfg_t) :: mat
    integer :: a, step
    omega = [300.0_rk, -200.0_rk, 500.0_rk]
    x(1,1,:) = [0.1_rk, -0.2_rk, 0.3_rk]; x(1,2,:) = [1.3_rk, 0.1_rk, -0.2_rk]
    x(1,3,:) = [0.2_rk, 0.9_rk, 0.4_rk]; x(1,4,:) = [0.3_rk, 0.2_rk, 1.7_rk]
    do a = 1, 4
      xa = x(1,a,:)
      v(1,a,:) = cross(omega, xa)
    end do
    call tet_gradients(1, 1, x, vol, grad, h)
    call tet_velocity_gradient(1, 1, v, grad, d, w)
    eps = 0.0_rk
    call check('rigid_rotation_strain_rate', maxval(abs(d(1,:))) < 1e-10_rk*norm2(omega), &
               'max |D| = '//r2s(maxval(abs(d(1,:))))//' 1/s for |omega| = '//r2s(norm2(omega)))
    s0 = [100.0e6_rk, -30.0e6_rk, -70.0e6_rk, 40.0e6_rk, -25.0e6_rk, 10.0e6_rk]
    s = s0
    i2_0 = j2(s); i3_0 = j3(s)
    dt = 1.0e-6_rk
    mat%strength = strength_elastic; mat%shear_modulus = 40.0e9_rk
    w_test = w(1,:)
    do step = 1, 10000   ! 10 ms of rotation: several full turns
      call one_step(mat, dt, d(1,:), 294.0_rk, s, eps, de, wd, wp)
    end do
    call check('objectivity_invariants', abs(j2(s)/i2_0 - 1) < 1e-12_rk .and. abs(j3(s)/i3_0 - 1) < 1e-11_rk, &
      'J2 drift '//r2s(j2(s)/i2_0 - 1)//', J3 drift '//r2s(j3(s)/i3_0 - 1)//' after 10^4 steps')
    call check('objectivity_rotates', maxval(abs(s - s0)) > 1e6_rk, 'the stress components did rotate')
    w_test = 0.0_rk
  end subroutine

  subroutine test_radial_return()
    type(material_cfg_t) :: mat
    real(rk) :: d(6), s(6), eps, de, wd, wp, dt, err
    integer :: k
    mat%shear_modulus = 40.0e9_rk; mat%yield_stress = 300.0e6_rk
    mat%strength = strength_perfectly_plastic
    s = 0; eps = 0; dt = 1.0e-7_rk
    d = [1.0e4_rk, -0.5e4_rk, -0.5e4_rk, 0.3e4_rk, 0.0_rk, -0.2e4_rk]
    do k = 1, 50
      call one_step(mat, dt, d, 294.0_rk, s, eps, de, wd, wp)
    end do
    call check('radial_return_perfect', abs(von_mises(s)/300.0e6_rk - 1) < 1e-12_rk .and. eps > 0, &
               'q = '//r2s(von_mises(s))//' Pa on sigma_y = 3e8, eps_p = '//r2s(eps))
    mat%strength = strength_linear_hardening; mat%hardening_modulus = 1.0e9_rk
    s = 0; eps = 0
    do k = 1, 50
      call one_step(mat, dt, d, 294.0_rk, s, eps, de, wd, wp)
    end do
    call check('radial_return_hardening', abs(von_mises(s)/(300.0e6_rk + 1.0e9_rk*eps) - 1) < 1e-12_rk, &
               'q = '//r2s(von_mises(s))//' = sigma_y(eps_p) = '//r2s(300.0e6_rk + 1.0e9_rk*eps))
    ! Johnson-Cook (OFHC copper): on the surface at the updated state
    mat%strength = strength_johnson_cook
    mat%jc_a = 90e6_rk; mat%jc_b = 292e6_rk; mat%jc_n = 0.31_rk; mat%jc_c = 0.025_rk; mat%jc_m = 1.09_rk
    mat%t_melt = 1356; mat%t_room = 294; mat%jc_rate0 = 1
    s = 0; eps = 0
    do k = 1, 50
      call one_step(mat, dt, d, 400.0_rk, s, eps, de, wd, wp)
    end do
    call check('radial_return_johnson_cook', abs(von_mises(s)/yield_stress(mat, eps, rate_of(d), 400.0_rk) - 1) &
               < 1e-9_rk, 'q = '//r2s(von_mises(s))//' Pa, eps_p = '//r2s(eps))
    ! plastic-rate form: on the surface at the rate de/dt of the step itself
    mat%jc_rate_form = jc_rate_plastic
    s = 0; eps = 0
    do k = 1, 50
      call one_step(mat, dt, d, 294.0_rk, s, eps, de, wd, wp)
    end do
    call check('radial_return_johnson_cook_plastic_rate', abs(von_mises(s)/((90e6_rk + 292e6_rk*eps**0.31_rk) &
               *(1 + 0.025_rk*log(de/dt))) - 1) < 1e-9_rk .and. de/dt > 1, 'q = '//r2s(von_mises(s))// &
               ' Pa at plastic rate '//r2s(de/dt)//' 1/s')
    mat%jc_rate_form = jc_rate_total
    ! hand value of the JC flow stress: eps_p = 0.5, rate 1e3/s, T = 500 K
    call check('johnson_cook_hand_value', abs(yield_stress(mat, 0.5_rk, 1.0e3_rk, 500.0_rk) &
               - (90e6_rk + 292e6_rk*0.5_rk**0.31_rk)*(1 + 0.025_rk*log(1.0e3_rk))*(1 - (206.0_rk/1062.0_rk)**1.09_rk)) &
               < 1e-6_rk, 'sigma_y(0.5, 1e3/s, 500 K) = '//r2s(yield_stress(mat, 0.5_rk, 1.0e3_rk, 500.0_rk)))
    ! the binomial series that replaces the power for small increments
    err = 0
    do k = -40, 40
      err = max(err, abs(power_ratio(k*0.0005_rk, 0.31_rk)/(1 + k*0.0005_rk)**0.31_rk - 1), &
                     abs(power_ratio(k*0.0005_rk, 1.09_rk)/(1 + k*0.0005_rk)**1.09_rk - 1))
    end do
    call check('power_ratio_series', err < 1e-13_rk, 'max relative error '//r2s(err)//' for |x| <= 0.02')
    mat%strength = strength_elastic
    s = 0; eps = 0
    call one_step(mat, dt, d, 294.0_rk, s, eps, de, wd, wp)
    call check('elastic_trial', abs(s(1) - 2*40.0e9_rk*dt*1.0e4_rk) < 1e-3_rk, 's_xx = 2 G dt d_xx')
  end subroutine

  !> One strength step of a single element through the block kernel.
  !> Johnson-Cook returns of a block iterate side by side (jc_returns):
  !> each element's result must be the one it gets alone in its block, for
  !> a block mixing elastic, first-yield, flowing, melted and strongly
  !> loaded elements (different iteration counts), in both rate forms.
  subroutine test_block_returns()
    integer, parameter :: nb = 11
    type(material_cfg_t) :: mat
    real(rk) :: d(nb,6), w(nb,3), soft(nb), temp(nb), hard(nb), s(nb,6), eps(nb), wd(nb), wp(nb)
    real(rk) :: d1(1,6), w1(1,3), hard1(1), s1(1,6), eps1(1), wd1(1), wp1(1), dt
    real(rk) :: hb(nb), sb(nb,6), eb(nb), wdb(nb), wpb(nb), zeros(nb), ones(nb)
    integer :: i, form, n_plastic
    logical :: same
    mat%shear_modulus = 46.0e9_rk
    mat%strength = strength_johnson_cook
    mat%jc_a = 90e6_rk; mat%jc_b = 292e6_rk; mat%jc_n = 0.31_rk; mat%jc_c = 0.025_rk; mat%jc_m = 1.09_rk
    mat%t_melt = 1356; mat%t_room = 294; mat%jc_rate0 = 1
    dt = 2.0e-8_rk
    zeros = 0.0_rk
    ones = 1.0_rk
    do i = 1, nb
      ! strain rates from 1e2 to 1e7 1/s, spins, prior strains 0 to 3
      d(i,:) = 10.0_rk**(2 + 0.5_rk*(i - 1))*[1.0_rk, -0.4_rk, -0.6_rk, 0.3_rk*i, -0.1_rk, 0.2_rk]
      w(i,:) = [1.0e4_rk*i, -2.0e3_rk, 5.0e3_rk]
      eps(i) = merge(0.0_rk, 0.3_rk*(i - 1), mod(i, 4) == 1)
      temp(i) = 294.0_rk + 90.0_rk*i
      soft(i) = thermal_softening(mat, temp(i))
      hard(i) = yield_stress(mat, eps(i), 0.0_rk, mat%t_room)
      s(i,:) = 0.2e8_rk*i*[1.0_rk, -0.5_rk, -0.5_rk, 0.1_rk, 0.2_rk, -0.1_rk]
    end do
    soft(7) = 0.0_rk                       ! melted: the closed form
    do form = 1, 2
      mat%jc_rate_form = merge(jc_rate_total, jc_rate_plastic, form == 1)
      hb = hard; sb = s; eb = eps
      call strength_block(mat, nb, nb, dt, d, w, soft, temp, zeros, ones, hb, sb, eb, wdb, wpb)
      same = .true.
      n_plastic = 0
      do i = 1, nb
        d1(1,:) = d(i,:); w1(1,:) = w(i,:); hard1(1) = hard(i); s1(1,:) = s(i,:); eps1(1) = eps(i)
        call strength_block(mat, 1, 1, dt, d1, w1, soft(i:i), temp(i:i), zeros(1:1), ones(1:1), hard1, s1, eps1, wd1, wp1)
        same = same .and. hb(i) == hard1(1) .and. all(sb(i,:) == s1(1,:)) .and. eb(i) == eps1(1) .and. &
               wdb(i) == wd1(1) .and. wpb(i) == wp1(1)
        if (eps1(1) > eps(i)) n_plastic = n_plastic + 1
      end do
      call check('block_returns_elementwise_'//trim(merge('total_rate  ', 'plastic_rate', form == 1)), &
                 same .and. n_plastic >= 5 .and. n_plastic < nb, 'each of 11 mixed elements as alone in its block: '//trim(merge('same     ', 'different', same))//' ('// &
                 itoa(n_plastic)//' flowing)')
    end do
  end subroutine

  subroutine one_step(mat, dt, d, temp, s, eps, de, wd, wp)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: dt, d(6), temp
    real(rk), intent(inout) :: s(6), eps
    real(rk), intent(out) :: de, wd, wp
    real(rk) :: db(1,6), wb(1,3), soft(1), hard(1), sb(1,6), eb(1), wdb(1), wpb(1)
    db(1,:) = d; wb(1,:) = w_test; sb(1,:) = s; eb(1) = eps
    soft(1) = thermal_softening(mat, temp)
    hard(1) = yield_stress(mat, eps, 0.0_rk, mat%t_room)   ! rate factor 1, no softening
    call strength_block(mat, 1, 1, dt, db, wb, soft, [temp], [0.0_rk], [1.0_rk], hard, sb, eb, wdb, wpb)
    de = eb(1) - eps
    s = sb(1,:); eps = eb(1); wd = wdb(1); wp = wpb(1)
  end subroutine

  real(rk) function rate_of(d)
    real(rk), intent(in) :: d(6)
    real(rk) :: dd(6)
    dd = d; dd(1:3) = dd(1:3) - sum(d(1:3))/3
    rate_of = sqrt(2.0_rk/3*(dd(1)**2 + dd(2)**2 + dd(3)**2 + 2*(dd(4)**2 + dd(5)**2 + dd(6)**2)))
  end function

  !> Stabilised tetrahedron (theory.md 8.1): the blend's limits, and the two
  !> pressure shares are p times the partial derivatives of J* (central
  !> differences), which is what makes the forces work-conjugate: near the
  !> nodes, on the share's ramp and beyond its onset, in compression and in
  !> tension, through both evaluation paths (series and library).
  subroutine test_blend()
    real(rk), parameter :: jb = 0.97_rk, p = 2.0e9_rk, dj = 1.0e-6_rk
    real(rk), parameter :: b0 = 0.03_rk, b1 = 0.1_rk, s1 = 0.3_rk
    real(rk), parameter :: jes(6) = [0.6_rk, 0.8_rk, 0.9_rk, 0.98_rk, 1.04_rk, 1.25_rk]
    real(rk) :: js, jp, jm, dbar, down, err, sh, sh_lo, sh_hi, j_lo, j_hi, je, x(4), dummy
    logical :: geo
    integer :: k, m
    call blended_volume_ratio(.true., 0.0_rk, 0.0_rk, s1, jb, 0.6_rk, x(1), dummy)
    call blended_volume_ratio(.true., 1.0_rk, 1.0_rk, s1, jb, 0.6_rk, x(2), dummy)
    call blended_volume_ratio(.false., 0.0_rk, 0.0_rk, s1, jb, 0.6_rk, x(3), dummy)
    call blended_volume_ratio(.false., 1.0_rk, 1.0_rk, s1, jb, 0.6_rk, x(4), dummy)
    call check('blend_limits', abs(x(1) - jb) < 1e-15_rk .and. abs(x(2) - 0.6_rk) < 1e-15_rk .and. &
               abs(x(3) - jb) < 1e-15_rk .and. abs(x(4) - 0.6_rk) < 1e-15_rk, 'beta = 0: Jbar, beta = 1: Je')
    err = 0.0_rk
    do k = 1, 2
      geo = k == 1
      do m = 1, size(jes)
        je = jes(m)
        call blended_volume_ratio(geo, b0, b1, s1, jb, je, js, sh)
        call blended_volume_ratio(geo, b0, b1, s1, jb + dj, je, jp, dummy)
        call blended_volume_ratio(geo, b0, b1, s1, jb - dj, je, jm, dummy)
        dbar = (jp - jm)/(2*dj)
        call blended_volume_ratio(geo, b0, b1, s1, jb, je + dj, jp, dummy)
        call blended_volume_ratio(geo, b0, b1, s1, jb, je - dj, jm, dummy)
        down = (jp - jm)/(2*dj)
        err = max(err, abs(blended_pressures(geo, .false., sh, p, js, jb, je)/(p*dbar) - 1), &
                       abs(blended_pressures(geo, .true., sh, p, js, jb, je)/(p*down) - 1))
      end do
    end do
    call check('blend_conjugate_pressures', err < 1e-8_rk, 'max relative error '//r2s(err)// &
               ' of p dJ*/dJbar and p dJ*/dJe (geometric and linear, Je/Jbar 0.62 .. 1.29)')
    ! the share: beta0 at the nodes' ratio, beta1 from the onset on, J* and share continuous there
    call blended_volume_ratio(.true., b0, b1, s1, jb, jb, js, sh)
    call blended_volume_ratio(.true., b0, b1, s1, jb, jb*exp(-s1*(1 - 1e-12_rk)), j_lo, sh_lo)
    call blended_volume_ratio(.true., b0, b1, s1, jb, jb*exp(-s1*(1 + 1e-12_rk)), j_hi, sh_hi)
    call check('blend_share_grows', sh == b0 .and. abs(sh_lo - b1) < 1e-10_rk .and. sh_hi == b1 .and. &
               abs(j_lo/j_hi - 1) < 1e-12_rk, 'share '//r2s(sh)//' at Je = Jbar, '//r2s(sh_lo)//' and '// &
               r2s(sh_hi)//' either side of the onset')
    call blended_volume_ratio(.true., b0, b1, s1, 1.0_rk, 1.0e-6_rk, x(1), dummy)
    call blended_volume_ratio(.false., b0, b1, s1, 1.0_rk, 1.0e-6_rk, x(2), dummy)
    call check('blend_geometric_barrier', x(1) < 0.26_rk .and. x(2) > 0.96_rk, &
               'Je -> 0: geometric J* -> 0 ('//r2s(x(1))//' at 1e-6), linear stays near 1 - beta0')
    call test_blend_power()
  end subroutine

  !> The geometric blend from series near 1 (hydro near_one_log,
  !> near_zero_exp): within 2 ulp of jbar exp(phi(ln(je/jbar))) with the
  !> library's log and exp over |je/jbar - 1| <= 0.1 (of jbar (je/jbar)**beta
  !> for a constant share), the library itself beyond; the block kernel gives
  !> the elemental's values bitwise.
  subroutine test_blend_power()
    integer, parameter :: n = 4001
    real(rk), parameter :: b0s(4) = [0.1_rk, 0.5_rk, 0.99_rk, 0.03_rk], b1s(4) = [0.1_rk, 0.5_rk, 0.99_rk, 0.1_rk]
    real(rk), parameter :: s1 = 0.05_rk
    real(rk) :: jb(n), je(n), jblk(n), jel(n), shb(n), she(n), ref, worst, phi, sl
    integer :: i, k
    worst = 0.0_rk
    do k = 1, size(b0s)
      do i = 1, n
        jb(i) = 0.6_rk + 0.8_rk*real(i, rk)/n
        je(i) = jb(i)*(0.85_rk + 0.3_rk*real(mod(7*i, n), rk)/n)   ! ratios 0.85 .. 1.15
        if (b0s(k) == b1s(k)) then
          ref = jb(i)*(je(i)/jb(i))**b0s(k)
        else
          call blend_exponent(b0s(k), b1s(k), s1, log(je(i)/jb(i)), phi, sl)
          ref = jb(i)*exp(phi)
        end if
        call blended_volume_ratio(.true., b0s(k), b1s(k), s1, jb(i), je(i), jel(i), she(i))
        worst = max(worst, abs(jel(i) - ref)/spacing(ref))
      end do
      call blended_volume_ratios(.true., b0s(k), b1s(k), s1, n, jb, je, jblk, shb)
      call check('blend_block_is_elemental_'//r2s(b0s(k))//'_'//r2s(b1s(k)), all(jblk == jel) .and. all(shb == she), &
                 'blended_volume_ratios equals blended_volume_ratio bitwise')
    end do
    call check('blend_power_ulp', worst <= 2.0_rk, 'largest difference from the library '//r2s(worst)//' ulp')
  end subroutine

  subroutine test_eos()
    real(rk) :: a, b, p, j, us, up
    ! linear: p = K (1/J - 1); K = 130 GPa, J = 0.99 -> 1.3131313 GPa
    call eos_linear_ab(130.0e9_rk, 0.99_rk, a, b)
    call check('eos_linear', abs(a - 1.3131313131e9_rk) < 1.0_rk .and. b == 0, 'p = '//r2s(a)//' Pa (1.3131313e9)')
    ! Mie-Grueneisen copper on its Hugoniot: up = 500 m/s, Us = c0 + s up = 4684.5 m/s,
    ! J = 1 - up/Us, e = up^2/2 -> p = rho0 Us up = 20.917 GPa (Rankine-Hugoniot)
    up = 500.0_rk; us = 3940.0_rk + 1.489_rk*up
    j = 1.0_rk - up/us
    call eos_mie_gruneisen_ab(8930.0_rk, 3940.0_rk, 1.489_rk, 2.02_rk, j, a, b)
    p = a + b*0.5_rk*up**2
    call check('eos_mie_gruneisen_hugoniot', abs(p/(8930.0_rk*us*up) - 1) < 1e-12_rk, &
               'p = '//r2s(p)//' Pa (rho0 Us up = 2.0917e10)')
    ! cold compression (e = 0), J = 0.9 (eta = 0.1): p_H = rho0 c0^2 eta/(1 - s eta)^2 = 1.9137e10,
    ! p = p_H (1 - gamma0 eta/2) = 1.7205e10 Pa
    call eos_mie_gruneisen_ab(8930.0_rk, 3940.0_rk, 1.489_rk, 2.02_rk, 0.9_rk, a, b)
    p = 8930.0_rk*3940.0_rk**2*0.1_rk/(1 - 0.1489_rk)**2*(1 - 0.101_rk)
    call check('eos_mie_gruneisen_cold', abs(a/p - 1) < 1e-12_rk .and. abs(b - 2.02_rk*8930) < 1e-9_rk, &
               'p = '//r2s(a)//' Pa (hand '//r2s(p)//')')
    ! tension, J = 1.01 (eta = -0.01): p = rho0 c0^2 eta (1 - gamma0 eta/2) = -1.4003e9 Pa
    call eos_mie_gruneisen_ab(8930.0_rk, 3940.0_rk, 1.489_rk, 2.02_rk, 1.01_rk, a, b)
    p = 8930.0_rk*3940.0_rk**2*(-0.01_rk)*(1 + 0.0101_rk)
    call check('eos_mie_gruneisen_tension', abs(a/p - 1) < 1e-12_rk .and. a < 0, 'p = '//r2s(a)//' Pa')
  end subroutine

  !> Fractured material: no tension, still compression; the criteria.
  subroutine test_fracture()
    type(material_cfg_t) :: mat
    real(rk) :: vol(2), h(2), trd(2), mass(2), j_old(2), j_new(2), w_dev(2), e(2), p(2), q(2), dt_el(2), visc(2)
    real(rk) :: e_i(2), p_i(2), q_i(2), damage, ef
    logical :: fractured
    mat%rho0 = 7850; mat%bulk_modulus = 160.0e9_rk; mat%shear_modulus = 80.0e9_rk
    ! element 1 expands (J 1 -> 1.002), element 2 is compressed (J 1 -> 0.998)
    vol = 1.0e-9_rk; h = 1.0e-3_rk; mass = mat%rho0*vol; j_old = 1; j_new = [1.002_rk, 0.998_rk]
    trd = (j_new - j_old)/1.0e-8_rk; w_dev = 0; e = 0; p = 0; q = 0
    e_i = e; p_i = p; q_i = q
    call volumetric_update(mat, 0.0_rk, 0.0_rk, 2, 1.0e-8_rk, vol, h, trd, mass, j_old, j_new, w_dev, &
                           [.false., .false.], e_i, p_i, q_i, dt_el, visc)
    call volumetric_update(mat, 0.0_rk, 0.0_rk, 2, 1.0e-8_rk, vol, h, trd, mass, j_old, j_new, w_dev, &
                           [.true., .true.], e, p, q, dt_el, visc)
    call check('fractured_no_tension', p_i(1) < 0 .and. p(1) == 0 .and. e(1) == 0, &
               'expanding: intact p = '//r2s(p_i(1))//' Pa, fractured p = '//r2s(p(1))//' Pa')
    call check('fractured_still_compression', p(2) > 0 .and. p(2) == p_i(2) .and. abs(p(2)/(160.0e9_rk*(1/0.998_rk - 1)) - 1) < 1e-12_rk, &
               'compressed: fractured p = '//r2s(p(2))//' Pa (K (1/J - 1) = '//r2s(160.0e9_rk*(1/0.998_rk - 1))//')')
    ! plastic strain intensity criterion: fractures when eps_p reaches eps_f
    mat%fracture = fracture_plastic_strain; mat%eps_f = 0.5_rk
    damage = 0
    call fracture_update(mat, 1.0e-8_rk, 0.01_rk, 0.49_rk, 1.0e9_rk, 0.0_rk, 294.0_rk, damage, fractured)
    call check('plastic_strain_below_eps_f', .not. fractured .and. abs(damage - 0.98_rk) < 1e-15_rk, 'D = '//r2s(damage))
    call fracture_update(mat, 1.0e-8_rk, 0.01_rk, 0.5_rk, 1.0e9_rk, 0.0_rk, 294.0_rk, damage, fractured)
    call check('plastic_strain_at_eps_f', fractured, 'D = '//r2s(damage))
    ! spall: mean stress below -p_spall
    mat%p_spall = 1.0e9_rk; damage = 0
    call fracture_update(mat, 1.0e-8_rk, 0.0_rk, 0.0_rk, 0.0_rk, -1.01e9_rk, 294.0_rk, damage, fractured)
    call check('spall_below_minus_p_spall', fractured, 'p = -1.01 GPa, p_spall = 1 GPa')
    call fracture_update(mat, 1.0e-8_rk, 0.0_rk, 0.0_rk, 0.0_rk, -0.99e9_rk, 294.0_rk, damage, fractured)
    call check('no_spall_above_minus_p_spall', .not. fractured, 'p = -0.99 GPa')
    ! Johnson-Cook 4340 steel (Johnson and Cook 1985): D1..D5 = 0.05, 3.44, -2.12, 0.002, 0.61;
    ! triaxiality 1/3, rate* = 1000, T* = 0.5 by hand: eps_f = 1.7764 x 1.013816 x 1.305
    mat%fracture = fracture_johnson_cook; mat%p_spall = 0
    mat%jc_d1 = 0.05_rk; mat%jc_d2 = 3.44_rk; mat%jc_d3 = -2.12_rk; mat%jc_d4 = 0.002_rk; mat%jc_d5 = 0.61_rk
    mat%jc_rate0 = 1.0_rk; mat%t_room = 294.0_rk; mat%t_melt = 1794.0_rk
    ef = (0.05_rk + 3.44_rk*exp(-2.12_rk/3))*(1 + 0.002_rk*log(1000.0_rk))*(1 + 0.61_rk*0.5_rk)
    call check('jc_fracture_strain', abs(jc_fracture_strain(mat, 1.0_rk/3, 1000.0_rk, 1044.0_rk)/ef - 1) < 1e-14_rk, &
               'eps_f = '//r2s(jc_fracture_strain(mat, 1.0_rk/3, 1000.0_rk, 1044.0_rk))//' (hand '//r2s(ef)//')')
    damage = 0
    call fracture_update(mat, 1.0e-5_rk, 0.01_rk, 0.01_rk, 3.0e9_rk, -1.0e9_rk, 1044.0_rk, damage, fractured)
    call check('jc_damage_increment', abs(damage - 0.01_rk/ef) < 1e-14_rk .and. .not. fractured, &
               'D = '//r2s(damage)//' (d_eps/eps_f = '//r2s(0.01_rk/ef)//')')
  end subroutine

  pure function cross(a, b)
    real(rk), intent(in) :: a(3), b(3)
    real(rk) :: cross(3)
    cross = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function

  pure real(rk) function j2(s)
    real(rk), intent(in) :: s(6)
    j2 = 0.5_rk*(s(1)**2 + s(2)**2 + s(3)**2) + s(4)**2 + s(5)**2 + s(6)**2
  end function

  pure real(rk) function j3(s)
    real(rk), intent(in) :: s(6)
    j3 = s(1)*(s(2)*s(3) - s(5)**2) - s(4)*(s(4)*s(3) - s(5)*s(6)) + s(6)*(s(4)*s(5) - s(2)*s(6))
  end function
end program test_kernels
