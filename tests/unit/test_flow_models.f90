!> Unit tests of the flow stress models beyond Johnson-Cook (issue 16):
!> Zerilli-Armstrong and Steinberg-Cochran-Guinan with their shear modulus
!> and melt models, against values computed by hand from the published
!> equations and OFHC copper constants (Zerilli and Armstrong 1987;
!> Steinberg 1996, half-hard OFHC copper), and their return through the
!> element's strength kernel.
program test_flow_models
  use udar_kinds, only: rk
  use udar_strings, only: r2s
  use udar_config, only: material_cfg_t, strength_zerilli_armstrong, strength_steinberg_guinan, &
      shear_steinberg_guinan, melt_steinberg_guinan, eos_mie_gruneisen, strength_mts, shear_mts, &
      strength_ptw, shear_ptw, strength_steinberg_lund
  use udar_strength, only: strength_block, von_mises, yield_stress
  use udar_flow_models, only: melt_temperature, shear_modulus_at, steinberg_lund_thermal
  use unit_checks, only: check, check_summary
  implicit none

  call test_zerilli_armstrong()
  call test_steinberg_guinan()
  call test_returns()
  call test_mts()
  call test_ptw()
  call test_steinberg_lund()
  call check_summary()

contains

  !> OFHC copper, Zerilli and Armstrong (1987): c0 = 65 MPa, c2 = 890 MPa,
  !> c3 = 0.0028 1/K, c4 = 0.000115 1/K.
  type(material_cfg_t) function za_copper() result(mat)
    mat%rho0 = 8930; mat%shear_modulus = 47.7e9_rk; mat%strength = strength_zerilli_armstrong
    mat%za_c0 = 65e6_rk; mat%za_c2 = 890e6_rk; mat%za_c3 = 0.0028_rk; mat%za_c4 = 0.000115_rk
    mat%specific_heat = 383; mat%t_melt = 1356
  end function

  !> Half-hard OFHC copper, Steinberg (1996): Y0 0.12 GPa, Ymax 0.64 GPa,
  !> beta 36, n 0.45, A 2.83 /Mbar, B 3.77e-4 /K, T_m0 1790 K, a 1.5,
  !> gamma0 2.02.
  type(material_cfg_t) function scg_copper() result(mat)
    mat%rho0 = 8930; mat%shear_modulus = 47.7e9_rk; mat%strength = strength_steinberg_guinan
    mat%eos = eos_mie_gruneisen; mat%c0 = 3940; mat%s = 1.489_rk; mat%gamma0 = 2.02_rk
    mat%sg_y0 = 0.12e9_rk; mat%sg_ymax = 0.64e9_rk; mat%sg_beta = 36; mat%sg_n = 0.45_rk
    mat%shear_model = shear_steinberg_guinan; mat%sg_a = 2.83e-11_rk; mat%sg_b = 3.77e-4_rk
    mat%melt_model = melt_steinberg_guinan; mat%t_melt = 1790; mat%melt_a = 1.5_rk
    mat%specific_heat = 383
  end function

  !> Annealed OFHC copper, MTS (Banerjee's constants as in the Uintah input
  !> file MTSPlasticAnnCopper.xml): sigma_a 40 MPa, no intrinsic term,
  !> g0e 1.6, rate0e 1e7/s, pe 2/3, qe 1, k/b^3 0.823e6 Pa/K, a0 2390 MPa,
  !> a1 12 MPa, a2 1.696 MPa s^1/2, alpha 2, sigma0es 770 MPa, g0es 0.2625,
  !> rate0es 1e7/s; G = 47.7 GPa - 3 GPa/(exp(180 K/T) - 1).
  type(material_cfg_t) function mts_copper() result(mat)
    mat%rho0 = 8930; mat%shear_modulus = 47.7e9_rk; mat%strength = strength_mts
    mat%shear_model = shear_mts; mat%mts_d = 3.0e9_rk; mat%mts_t0 = 180
    mat%mts_sigma_a = 40e6_rk; mat%mts_g0e = 1.6_rk; mat%mts_rate0e = 1e7_rk; mat%mts_pe = 2.0_rk/3.0_rk
    mat%mts_qe = 1; mat%mts_kb3 = 0.823e6_rk; mat%mts_a0 = 2390e6_rk; mat%mts_a1 = 12e6_rk
    mat%mts_a2 = 1.696e6_rk; mat%mts_alpha = 2; mat%mts_sigma0es = 770e6_rk; mat%mts_g0es = 0.2625_rk
    mat%mts_rate0es = 1e7_rk; mat%specific_heat = 383; mat%t_melt = 1356
  end function

  !> The MTS model: the shear modulus and the flow stress at a given internal
  !> stress against values computed by hand; the internal stress of the
  !> element's step-by-step return against the evolution equation solved
  !> by a fine Runge-Kutta integration written here; the return on the surface.
  subroutine test_mts()
    type(material_cfg_t) :: mat
    real(rk) :: g, sy, s(6), eps, dt, d(6), rate, err, se_ref, x, h, k1, k2, k3, k4
    integer :: k, n
    mat = mts_copper()
    ! 47.7 - 3/(exp(180/298) - 1) GPa
    g = shear_modulus_at(mat, 0.0_rk, 298.0_rk, 1.0_rk)
    call check('mts_shear_modulus_hand_value', abs(g/44.083237e9_rk - 1) < 1e-7_rk, &
               'G(298 K) = '//r2s(g)//' Pa (hand: 44.083237 GPa)')
    ! 40 + S_e sigma_e G/G0, S_e = (1 - 0.823e6 298/(1.6 G) ln(1e7/1e3))^1.5 = 0.952348
    sy = yield_stress(mat, 175.374e6_rk, 1.0e3_rk, 298.0_rk)
    call check('mts_copper_hand_value', abs(sy/194.353e6_rk - 1) < 1e-5_rk, &
               'sigma(sigma_e 175.374 MPa, 1e3/s, 298 K) = '//r2s(sy)//' Pa (hand: 194.353 MPa)')
    call check('mts_virgin', abs(yield_stress(mat, 0.0_rk, 1.0e3_rk, 298.0_rk) - 40e6_rk) < 1e-6_rk, &
               'sigma(sigma_e = 0) = sigma_a = 40 MPa')
    ! uniaxial-strain loading at 298 K: the steps' internal stress against the ODE
    dt = 1.0e-8_rk
    d = [-1.0e4_rk, 0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk]
    rate = 2.0_rk/3.0_rk*1.0e4_rk
    s = 0; eps = 0; x = 0; err = 0
    do k = 1, 2000
      call step_mts(mat, dt, d, 298.0_rk, s, eps, x)
      if (eps > 0) err = max(err, abs(von_mises(s)/yield_stress(mat, x, rate, 298.0_rk) - 1))
    end do
    call check('mts_return_on_surface', eps > 0.1_rk .and. err < 1e-12_rk, &
               'eps_p = '//r2s(eps)//', largest |q/sigma - 1| '//r2s(err))
    ! d(sigma_e)/d(eps_p) = theta0 (1 - tanh(2 X)/tanh 2), X = sigma_e/sigma_es, RK4 in 10^4 steps
    se_ref = 0
    n = 10000
    h = eps/n
    do k = 1, n
      k1 = mts_rate_ref(se_ref, g, rate)
      k2 = mts_rate_ref(se_ref + 0.5_rk*h*k1, g, rate)
      k3 = mts_rate_ref(se_ref + 0.5_rk*h*k2, g, rate)
      k4 = mts_rate_ref(se_ref + h*k3, g, rate)
      se_ref = se_ref + h/6*(k1 + 2*k2 + 2*k3 + k4)
    end do
    call check('mts_internal_stress_against_the_ode', abs(x/se_ref - 1) < 1e-3_rk, &
               'sigma_e = '//r2s(x)//' Pa at eps_p '//r2s(eps)//' against '//r2s(se_ref)//' Pa (RK4)')
  end subroutine

  !> The MTS copper's hardening rate at 298 K, written out for the test.
  real(rk) function mts_rate_ref(se, g, rate) result(theta)
    real(rk), intent(in) :: se, g, rate
    real(rk) :: theta0, ses
    theta0 = 2390e6_rk + 12e6_rk*log(rate) + 1.696e6_rk*sqrt(rate)
    ses = 770e6_rk*(rate/1e7_rk)**(0.823e6_rk*298/(0.2625_rk*g))
    theta = theta0*(1 - tanh(2*se/ses)/tanh(2.0_rk))
  end function

  !> One MTS strength step: x is the internal stress (strength_block's hard).
  subroutine step_mts(mat, dt, d, temp, s, eps, x)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: dt, d(6), temp
    real(rk), intent(inout) :: s(6), eps, x
    real(rk) :: db(1,6), wb(1,3), soft(1), hard(1), sb(1,6), eb(1), wdb(1), wpb(1)
    db(1,:) = d; wb = 0; sb(1,:) = s; eb(1) = eps; soft = 1; hard = x
    call strength_block(mat, 1, 1, dt, db, wb, soft, [temp], [0.0_rk], [1.0_rk], hard, sb, eb, wdb, wpb)
    s = sb(1,:); eps = eb(1); x = hard(1)
  end subroutine

  !> OFHC copper, Preston-Tonks-Wallace (2003; the constants as in the
  !> Uintah documentation): theta 0.025, p 2, s0 0.0085, sinf 0.00055, kappa
  !> 0.11, gamma 1e-5, y0 = yinf = 1e-4, y1 0.094, y2 0.575, beta 0.25, M
  !> 63.54 g/mol, G = 51.8 GPa (1 - 0.2 T/T_m), T_m 1356 K. The values below
  !> were computed from the paper's equations by an independent Python
  !> evaluation (issue 16's research notes), to six digits.
  type(material_cfg_t) function ptw_copper() result(mat)
    mat%rho0 = 8930; mat%shear_modulus = 51.8e9_rk; mat%strength = strength_ptw
    mat%shear_model = shear_ptw; mat%ptw_alpha = 0.2_rk; mat%t_melt = 1356
    mat%ptw_theta = 0.025_rk; mat%ptw_p = 2; mat%ptw_s0 = 0.0085_rk; mat%ptw_sinf = 0.00055_rk
    mat%ptw_kappa = 0.11_rk; mat%ptw_gamma = 1e-5_rk; mat%ptw_y0 = 1e-4_rk; mat%ptw_yinf = 1e-4_rk
    mat%ptw_y1 = 0.094_rk; mat%ptw_y2 = 0.575_rk; mat%ptw_beta = 0.25_rk; mat%ptw_molar_mass = 0.06354_rk
    mat%specific_heat = 383
  end function

  subroutine test_ptw()
    type(material_cfg_t) :: mat
    real(rk) :: s(6), eps, dt, d(6), err, rate
    integer :: k
    mat = ptw_copper()
    call ptw_value(mat, 'ptw_copper_1_per_s_eps0', 0.0_rk, 1.0_rk, 9.905e6_rk)
    call ptw_value(mat, 'ptw_copper_1_per_s_eps0.2', 0.2_rk, 1.0_rk, 277.637e6_rk)
    call ptw_value(mat, 'ptw_copper_1e4_per_s_eps0', 0.0_rk, 1.0e4_rk, 51.819e6_rk)
    call ptw_value(mat, 'ptw_copper_1e4_per_s_eps0.2', 0.2_rk, 1.0e4_rk, 336.657e6_rk)
    dt = 1.0e-8_rk
    d = [-1.0e4_rk, 0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk]
    rate = 2.0_rk/3.0_rk*1.0e4_rk
    s = 0; eps = 0; err = 0
    do k = 1, 1000
      call step(mat, dt, d, 298.0_rk, 0.0_rk, 1.0_rk, s, eps)
      if (eps > 0) err = max(err, abs(von_mises(s)/yield_stress(mat, eps, rate, 298.0_rk) - 1))
    end do
    call check('ptw_return_on_surface', eps > 0.05_rk .and. err < 1e-12_rk, &
               'eps_p = '//r2s(eps)//', largest |q/sigma - 1| '//r2s(err))
  end subroutine

  !> The PTW flow stress at 298 K against a value computed independently.
  subroutine ptw_value(mat, name, e, r, expected)
    type(material_cfg_t), intent(in) :: mat
    character(len=*), intent(in) :: name
    real(rk), intent(in) :: e, r, expected
    real(rk) :: sy
    sy = yield_stress(mat, e, r, 298.0_rk)
    call check(name, abs(sy/expected - 1) < 1e-4_rk, 'sigma = '//r2s(sy)//' Pa (computed independently: '// &
               r2s(expected)//')')
  end subroutine

  subroutine test_zerilli_armstrong()
    type(material_cfg_t) :: mat
    real(rk) :: sy
    mat = za_copper()
    ! 65 + 890 sqrt(0.1) exp(298 (0.000115 ln 1000 - 0.0028)) MPa
    sy = yield_stress(mat, 0.1_rk, 1.0e3_rk, 298.0_rk)
    call check('za_copper_hand_value', abs(sy/219.819154e6_rk - 1) < 1e-8_rk, &
               'sigma(0.1, 1e3/s, 298 K) = '//r2s(sy)//' Pa (hand: 219.819154 MPa)')
    ! rates below za_rate0 count as za_rate0: 65 + 890 sqrt(0.1) exp(-298 0.0028) MPa
    sy = yield_stress(mat, 0.1_rk, 1.0e-3_rk, 298.0_rk)
    call check('za_rate_floor', abs(sy/187.184099e6_rk - 1) < 1e-8_rk, &
               'sigma(0.1, 1e-3/s, 298 K) = '//r2s(sy)//' Pa (at za_rate0 = 1/s: 187.184099 MPa)')
    call check('za_virgin', abs(yield_stress(mat, 0.0_rk, 1.0e3_rk, 298.0_rk) - 65e6_rk) < 1e-6_rk, &
               'FCC: sigma(0) = c0 = 65 MPa')
    call check('za_no_strength_above_melt', yield_stress(mat, 0.1_rk, 1.0e3_rk, 1400.0_rk) == 0, &
               'T = 1400 K > t_melt = 1356 K: sigma = 0')
    ! the BCC terms: c1 exp(...) + c5 eps^n
    mat%za_c2 = 0; mat%za_c1 = 1000e6_rk; mat%za_c5 = 266e6_rk; mat%za_n = 0.289_rk
    sy = yield_stress(mat, 0.2_rk, 1.0e3_rk, 298.0_rk)
    call check('za_bcc_hand_value', abs(sy - (65e6_rk + 1000e6_rk*exp(298*(0.000115_rk*log(1.0e3_rk) - 0.0028_rk)) &
               + 266e6_rk*0.2_rk**0.289_rk)) < 1e-6_rk*sy, 'sigma = '//r2s(sy)//' Pa')
  end subroutine

  subroutine test_steinberg_guinan()
    type(material_cfg_t) :: mat
    real(rk) :: sy, g, tm
    mat = scg_copper()
    ! 120 (1 + 36 0.1)^0.45 MPa at p = 0, T = t0 = 300 K
    sy = yield_stress(mat, 0.1_rk, 1.0e3_rk, 300.0_rk)
    call check('scg_copper_hand_value', abs(sy/238.463696e6_rk - 1) < 1e-8_rk, &
               'Y(0.1, p = 0, 300 K) = '//r2s(sy)//' Pa (hand: 238.463696 MPa)')
    ! G0 (1 + 2.83e-11 1e10 / 1.05^(1/3) - 3.77e-4 200)
    g = shear_modulus_at(mat, 10.0e9_rk, 500.0_rk, 1.05_rk)
    call check('sg_shear_modulus_hand_value', abs(g/57.3847545e9_rk - 1) < 1e-8_rk, &
               'G(10 GPa, 500 K, eta 1.05) = '//r2s(g)//' Pa (hand: 57.3847545 GPa)')
    sy = yield_stress(mat, 0.1_rk, 1.0e3_rk, 500.0_rk, 10.0e9_rk, 1.05_rk)
    call check('scg_flow_scales_with_g', abs(sy/286.880097e6_rk - 1) < 1e-8_rk, &
               'Y(0.1, 10 GPa, 500 K, eta 1.05) = '//r2s(sy)//' Pa (hand: 286.880097 MPa)')
    call check('scg_ymax', abs(yield_stress(mat, 2.0_rk, 1.0e3_rk, 300.0_rk) - 0.64e9_rk) < 1e-6_rk, &
               'Y(eps_p = 2) = Ymax = 0.64 GPa')
    ! 1790 exp(3 (1 - 1/1.1)) 1.1^(2 (2.02 - 1.5 - 1/3)) K
    tm = melt_temperature(mat, 1.1_rk)
    call check('sg_melt_hand_value', abs(tm/2436.40931_rk - 1) < 1e-8_rk, &
               'T_m(eta 1.1) = '//r2s(tm)//' K (hand: 2436.40931 K)')
    call check('scg_no_strength_above_melt', yield_stress(mat, 0.1_rk, 1.0e3_rk, 1800.0_rk) == 0 .and. &
               yield_stress(mat, 0.1_rk, 1.0e3_rk, 1800.0_rk, 0.0_rk, 1.1_rk) > 0, &
               '1800 K: melted at eta 1 (1790 K), solid at eta 1.1 (2436 K)')
  end subroutine

  !> A tantalum-like Steinberg-Lund material: U_k = 0.31 eV and C1 =
  !> 0.71e6/s as NairnMPM's defaults attributed to Steinberg and Lund (1989)
  !> and Spheral's tantalum test (2 U_k/k = 7195 K); Y_P, C2 and the
  !> athermal part (Steinberg-Guinan's tantalum beta, n, Ymax with Y_A =
  !> 0.375 GPa) are of the right size but not checked against the paper's
  !> table: the checks below are exact for whatever constants are given.
  type(material_cfg_t) function sl_tantalum() result(mat)
    mat%rho0 = 16690; mat%shear_modulus = 69e9_rk; mat%strength = strength_steinberg_lund
    mat%sg_y0 = 0.375e9_rk; mat%sg_ymax = 1.1e9_rk; mat%sg_beta = 10; mat%sg_n = 0.1_rk
    mat%sl_yp = 0.82e9_rk; mat%sl_uk = 0.31_rk*1.602176634e-19_rk; mat%sl_c1 = 0.71e6_rk; mat%sl_c2 = 1.2e3_rk
    mat%specific_heat = 140; mat%t_melt = 4340
  end function

  !> Lund's rate law: the thermally activated stress against the rate law
  !> evaluated forwards here (a rate from a chosen Y_T), its cap at the
  !> Peierls stress, its fall with temperature, finite where the
  !> exponential overflows, and the flow stress and the return through the
  !> element's strength kernel.
  subroutine test_steinberg_lund()
    type(material_cfg_t) :: mat
    real(rk), parameter :: k_b = 1.380649e-23_rk
    real(rk) :: y_star, rate, y_t, a, sy, s(6), eps, dt, d(6), err, rate_max
    integer :: k
    mat = sl_tantalum()
    y_star = 0.4_rk*mat%sl_yp
    a = 2*mat%sl_uk/(k_b*300)
    rate = 1/(exp(a*(1 - y_star/mat%sl_yp)**2)/mat%sl_c1 + mat%sl_c2/y_star)
    y_t = steinberg_lund_thermal(mat, rate, 300.0_rk)
    call check('sl_inverts_the_rate_law', abs(y_t/y_star - 1) < 1e-10_rk, &
               'Y_T = '//r2s(y_t)//' Pa at rate '//r2s(rate)//' /s, 300 K (chosen: '//r2s(y_star)//')')
    y_star = 0.97_rk*mat%sl_yp
    rate = 1/(exp(a*(1 - y_star/mat%sl_yp)**2)/mat%sl_c1 + mat%sl_c2/y_star)
    y_t = steinberg_lund_thermal(mat, rate, 300.0_rk)
    call check('sl_inverts_near_the_peierls_stress', abs(y_t/y_star - 1) < 1e-10_rk, &
               'Y_T = '//r2s(y_t)//' Pa at rate '//r2s(rate)//' /s (chosen: '//r2s(y_star)//')')
    rate_max = 1/(1/mat%sl_c1 + mat%sl_c2/mat%sl_yp)
    call check('sl_capped_at_the_peierls_stress', steinberg_lund_thermal(mat, 2*rate_max, 300.0_rk) == mat%sl_yp, &
               'rates above 1/(1/C1 + C2/Y_P) = '//r2s(rate_max)//' /s give Y_P')
    call check('sl_hotter_is_softer', steinberg_lund_thermal(mat, 1.0e3_rk, 600.0_rk) < &
               0.9_rk*steinberg_lund_thermal(mat, 1.0e3_rk, 300.0_rk), &
               'Y_T(1e3/s, 600 K) = '//r2s(steinberg_lund_thermal(mat, 1.0e3_rk, 600.0_rk))//', 300 K: '// &
               r2s(steinberg_lund_thermal(mat, 1.0e3_rk, 300.0_rk)))
    ! at 2 K the exponential of the rate law overflows; its logarithm does not
    y_t = steinberg_lund_thermal(mat, 1.0e3_rk, 2.0_rk)
    call check('sl_cold_finite', y_t > 0.9_rk*mat%sl_yp .and. y_t <= mat%sl_yp, 'Y_T(1e3/s, 2 K) = '//r2s(y_t))
    ! without drag a slow enough rate is reached by thermal activation alone
    mat%sl_c2 = 0
    call check('sl_no_drag_slow_rate', steinberg_lund_thermal(mat, 1.0e-5_rk, 1000.0_rk) == 0, &
               'C2 = 0, 1e-5/s at 1000 K: Y_T = '//r2s(steinberg_lund_thermal(mat, 1.0e-5_rk, 1000.0_rk)))
    mat = sl_tantalum()
    ! flow stress: (Y_T + 375 (1 + 10 0.2)^0.1 MPa) G/G0 with G constant
    y_star = 0.4_rk*mat%sl_yp
    rate = 1/(exp(a*(1 - y_star/mat%sl_yp)**2)/mat%sl_c1 + mat%sl_c2/y_star)
    sy = yield_stress(mat, 0.2_rk, rate, 300.0_rk)
    call check('sl_flow_stress_hand_value', abs(sy/(y_star + 418.546190e6_rk) - 1) < 1e-8_rk, &
               'Y(0.2) = '//r2s(sy)//' Pa (hand: 0.4 Y_P + 418.546190 MPa)')
    ! return through the element's kernel: on the surface at the step's rate
    dt = 1.0e-8_rk
    d = [-1.0e4_rk, 0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk]
    rate = 2.0_rk/3.0_rk*1.0e4_rk
    s = 0; eps = 0; err = 0
    do k = 1, 200
      call step(mat, dt, d, 300.0_rk, 0.0_rk, 1.0_rk, s, eps)
      if (eps > 0) err = max(err, abs(von_mises(s)/yield_stress(mat, eps, rate, 300.0_rk) - 1))
    end do
    call check('sl_return_on_surface', eps > 0.005_rk .and. err < 1e-12_rk, &
               'eps_p = '//r2s(eps)//', largest |q/Y - 1| '//r2s(err))
  end subroutine

  !> Uniaxial-strain loading of one element through strength_block: after
  !> each plastic step the deviator lies on the flow surface at its new
  !> plastic strain (and the state's G); melt takes the deviator away.
  subroutine test_returns()
    type(material_cfg_t) :: mat
    real(rk) :: s(6), eps, dt, d(6), err, rate, q
    integer :: k
    dt = 1.0e-8_rk
    d = [-1.0e4_rk, 0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk]
    rate = 2.0_rk/3.0_rk*1.0e4_rk      ! equivalent rate of dev(d)
    mat = za_copper()
    s = 0; eps = 0; err = 0
    do k = 1, 200
      call step(mat, dt, d, 400.0_rk, 0.0_rk, 1.0_rk, s, eps)
      if (eps > 0) err = max(err, abs(von_mises(s)/yield_stress(mat, eps, rate, 400.0_rk) - 1))
    end do
    call check('za_return_on_surface', eps > 0.01_rk .and. err < 1e-12_rk, &
               'eps_p = '//r2s(eps)//', largest |q/sigma - 1| '//r2s(err))
    mat = scg_copper()
    s = 0; eps = 0; err = 0
    do k = 1, 200
      call step(mat, dt, d, 500.0_rk, 5.0e9_rk, 1.03_rk, s, eps)
      if (eps > 0) err = max(err, abs(von_mises(s)/yield_stress(mat, eps, rate, 500.0_rk, 5.0e9_rk, 1.03_rk) - 1))
    end do
    call check('scg_return_on_surface', eps > 0.01_rk .and. err < 1e-12_rk, &
               'eps_p = '//r2s(eps)//', largest |q/Y - 1| '//r2s(err))
    ! the elastic trial takes G(p, T): one small step from zero
    s = 0; eps = 0
    call step(mat, dt, [1.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk, 0.0_rk], 500.0_rk, 10.0e9_rk, 1.05_rk, s, eps)
    call check('sg_trial_modulus', abs(s(1)/(2*57.3847545e9_rk*dt*(2.0_rk/3.0_rk)) - 1) < 1e-8_rk, &
               's_xx = '//r2s(s(1))//' = 2 G(p, T) dt dev(d)_xx')
    ! melted: no deviator left
    s = 0; eps = 0
    do k = 1, 50
      call step(mat, dt, d, 500.0_rk, 0.0_rk, 1.0_rk, s, eps)
    end do
    q = von_mises(s)
    call step(mat, dt, d, 1800.0_rk, 0.0_rk, 1.0_rk, s, eps)
    call check('scg_melt_return', q > 1e8_rk .and. von_mises(s) == 0, &
               'q = '//r2s(q)//' Pa at 500 K, '//r2s(von_mises(s))//' Pa above melt')
  end subroutine

  !> One strength step of a single element at temperature temp, pressure p
  !> and eta = rho/rho0.
  subroutine step(mat, dt, d, temp, p, eta, s, eps)
    type(material_cfg_t), intent(in) :: mat
    real(rk), intent(in) :: dt, d(6), temp, p, eta
    real(rk), intent(inout) :: s(6), eps
    real(rk) :: db(1,6), wb(1,3), soft(1), hard(1), sb(1,6), eb(1), wdb(1), wpb(1)
    db(1,:) = d; wb = 0; sb(1,:) = s; eb(1) = eps; soft = 1; hard = 0
    call strength_block(mat, 1, 1, dt, db, wb, soft, [temp], [p], [eta], hard, sb, eb, wdb, wpb)
    s = sb(1,:); eps = eb(1)
  end subroutine
end program test_flow_models
