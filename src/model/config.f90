!> The resolved input deck: plain data, filled by udar_deck, read by the drivers.
!> Defaults live here (one place); udar_deck reports which were left at default.
!> All values SI.
module udar_config
  use udar_kinds, only: rk, max_name_len, max_path_len
  implicit none
  private
  public :: run_cfg_t, mesh_cfg_t, material_cfg_t, part_cfg_t, boundary_cfg_t, &
            numerics_cfg_t, output_cfg_t, contact_cfg_t, gauge_cfg_t, config_t
  public :: eos_linear, eos_mie_gruneisen, strength_none, strength_elastic, &
            strength_perfectly_plastic, strength_linear_hardening, strength_johnson_cook, &
            strength_zerilli_armstrong, strength_steinberg_guinan, strength_mts, strength_ptw, strength_steinberg_lund, &
            shear_constant, shear_steinberg_guinan, shear_mts, shear_ptw, &
            melt_constant, melt_steinberg_guinan, &
            bc_fixed, bc_symmetry, bc_rigid_wall, wall_frictionless, wall_sticking, wall_coulomb, &
            tet_plain, tet_nodal, tet_stabilised, tet_stabilised_linear, &
            jc_rate_total, jc_rate_plastic, contact_weights_distance, contact_weights_area, &
            overlap_report, overlap_move, fracture_none, fracture_plastic_strain, fracture_johnson_cook, &
            geometry_solid, geometry_axisymmetric, geometry_plane_strain, eroded_free_nodes, eroded_particles

  ! integer codes the kernels dispatch on (strings stay in the deck)
  integer, parameter :: eos_linear = 1, eos_mie_gruneisen = 2
  integer, parameter :: strength_none = 0, strength_elastic = 1, strength_perfectly_plastic = 2, &
                        strength_linear_hardening = 3, strength_johnson_cook = 4, &
                        strength_zerilli_armstrong = 5, strength_steinberg_guinan = 6, strength_mts = 7, &
                        strength_ptw = 8, strength_steinberg_lund = 9
  !> the shear modulus: the deck's constant, or Steinberg-Guinan's G(p, T)
  integer, parameter :: shear_constant = 0, shear_steinberg_guinan = 1, shear_mts = 2, shear_ptw = 3
  !> the melt temperature: the deck's t_melt, or Steinberg-Guinan's T_m(rho)
  integer, parameter :: melt_constant = 0, melt_steinberg_guinan = 1
  integer, parameter :: bc_fixed = 1, bc_symmetry = 2, bc_rigid_wall = 3
  integer, parameter :: wall_frictionless = 1, wall_sticking = 2, wall_coulomb = 3
  !> tetrahedron formulations (&numerics tet_formulation; doc/theory.md section 8)
  integer, parameter :: tet_plain = 1, tet_nodal = 2, tet_stabilised = 3, tet_stabilised_linear = 4
  integer, parameter :: jc_rate_total = 1, jc_rate_plastic = 2
  integer, parameter :: contact_weights_distance = 1, contact_weights_area = 2
  integer, parameter :: overlap_report = 1, overlap_move = 2
  integer, parameter :: fracture_none = 0, fracture_plastic_strain = 1, fracture_johnson_cook = 2
  !> what an eroded element becomes: nothing (its mass stays at its nodes,
  !> which move freely once all their elements are gone) or a particle
  !> (its mass, momentum, energy and state; theory.md section 15)
  integer, parameter :: eroded_free_nodes = 0, eroded_particles = 1
  !> what the mesh is (&mesh geometry): 3D tetrahedra, or 2D triangles in
  !> the (r, z) half plane about the y axis or in the (x, y) plane per metre
  integer, parameter :: geometry_solid = 1, geometry_axisymmetric = 2, geometry_plane_strain = 3

  type :: run_cfg_t
    character(len=256) :: title = 'udar run'
    real(rk) :: t_end = -1.0_rk            !< s, required
    real(rk) :: dt_safety = 0.9_rk         !< -, fraction of the stable step estimate (theory.md section 9)
    real(rk) :: dt_initial = 0.0_rk        !< s, 0 = stable step
    real(rk) :: dt_max = huge(1.0_rk)      !< s
    integer  :: max_cycles = huge(1)       !< -
    integer  :: cycle_print = 100          !< -, stdout progress line every N cycles
    real(rk) :: energy_error_limit = 0.2_rk !< -, |energy error| above this stops the run
    real(rk) :: wall_limit = 0.0_rk        !< s of wall time, 0 = none: checkpoint and stop before it
    real(rk) :: end_kinetic_fraction = 0.0_rk !< -, end when the kinetic energy falls below this share of its peak (0 = never)
    real(rk) :: dt_warn_ratio = 0.1_rk     !< -, warn when the stable step falls below this share of the first one (0 = never)
    !> -, on more than one rank: repartition (through a checkpoint) when the
    !> slowest rank's element work exceeds the mean by more than this share
    !> (0 = never)
    real(rk) :: rebalance_imbalance = 0.0_rk
  end type

  type :: mesh_cfg_t
    character(len=max_path_len) :: file = ''   !< gmsh .msh, relative to the deck's folder
    real(rk) :: scale = 1.0_rk                 !< -, multiplies coordinates (0.001 for mm)
    integer  :: geometry = geometry_solid      !< solid (3D), axisymmetric or plane_strain (2D)
  end type

  type :: material_cfg_t
    character(len=max_name_len) :: name = ''
    real(rk) :: rho0 = -1.0_rk                 !< kg/m3
    integer  :: eos = eos_linear
    real(rk) :: bulk_modulus = -1.0_rk         !< Pa (linear EOS)
    real(rk) :: c0 = -1.0_rk, s = 0.0_rk, gamma0 = 0.0_rk   !< Mie-Grueneisen: m/s, -, -
    integer  :: strength = strength_elastic
    real(rk) :: shear_modulus = -1.0_rk        !< Pa
    real(rk) :: youngs_modulus = -1.0_rk       !< Pa (alternative with poisson_ratio)
    real(rk) :: poisson_ratio = -1.0_rk        !< -
    real(rk) :: yield_stress = -1.0_rk         !< Pa
    real(rk) :: hardening_modulus = 0.0_rk     !< Pa, plastic modulus d(sigma_y)/d(eps_p)
    real(rk) :: jc_a = -1.0_rk, jc_b = 0.0_rk, jc_n = 1.0_rk, jc_c = 0.0_rk, jc_m = 1.0_rk  !< Pa, Pa, -, -, -
    real(rk) :: jc_rate0 = 1.0_rk              !< 1/s
    integer  :: jc_rate_form = jc_rate_total   !< strain rate in the rate term: total or plastic
    !> Zerilli-Armstrong (1987): sigma = c0 + (c1 + c2 eps_p^1/2) exp(-c3 T + c4 T ln(rate/rate0)) + c5 eps_p^n
    real(rk) :: za_c0 = 0.0_rk, za_c1 = 0.0_rk, za_c2 = 0.0_rk   !< Pa, Pa, Pa
    real(rk) :: za_c3 = 0.0_rk, za_c4 = 0.0_rk                   !< 1/K, 1/K
    real(rk) :: za_c5 = 0.0_rk, za_n = 1.0_rk                    !< Pa, -
    real(rk) :: za_rate0 = 1.0_rk                                !< 1/s
    !> Steinberg-Cochran-Guinan (1980): Y = min(y0 (1 + beta (eps_p + eps_i))^n, ymax) G/G0
    real(rk) :: sg_y0 = -1.0_rk, sg_ymax = -1.0_rk               !< Pa, Pa
    real(rk) :: sg_beta = 0.0_rk, sg_n = 0.0_rk, sg_eps_i = 0.0_rk   !< -, -, -
    !> Steinberg-Lund (1989): Y = (Y_T(rate, T) + min(sg_y0 (1 + beta (eps_p + eps_i))^n, ymax)) G/G0,
    !> rate = [exp(2 U_k/(k T) (1 - Y_T/Y_P)^2)/C1 + C2/Y_T]^-1, Y_T <= Y_P
    real(rk) :: sl_yp = -1.0_rk, sl_uk = -1.0_rk                 !< Pa, J
    real(rk) :: sl_c1 = -1.0_rk, sl_c2 = 0.0_rk                  !< 1/s, Pa s
    integer  :: shear_model = shear_constant
    !> Steinberg-Guinan shear modulus: G = G0 (1 + A p eta^(-1/3) - B (T - t0)), eta = rho/rho0
    real(rk) :: sg_a = 0.0_rk, sg_b = 0.0_rk, sg_t0 = 300.0_rk    !< 1/Pa, 1/K, K
    !> Mechanical Threshold Stress (Follansbee and Kocks 1988; Banerjee's form): sigma = sigma_a
    !> + (S_i sigma_i + S_e sigma_e) G/G0, sigma_e evolving with theta0 (1 - F) + theta_iv F
    real(rk) :: mts_sigma_a = 0.0_rk, mts_sigma_i = 0.0_rk       !< Pa, Pa
    real(rk) :: mts_g0i = 1.0_rk, mts_rate0i = 1.0e7_rk          !< -, 1/s
    real(rk) :: mts_pi = 1.0_rk, mts_qi = 1.0_rk                 !< -, -
    real(rk) :: mts_g0e = 1.0_rk, mts_rate0e = 1.0e7_rk          !< -, 1/s
    real(rk) :: mts_pe = 1.0_rk, mts_qe = 1.0_rk                 !< -, -
    real(rk) :: mts_kb3 = 0.0_rk                                 !< Pa/K, Boltzmann's constant over b^3
    real(rk) :: mts_a0 = 0.0_rk, mts_a1 = 0.0_rk                 !< Pa, Pa
    real(rk) :: mts_a2 = 0.0_rk, mts_a3 = 0.0_rk                 !< Pa s^1/2, Pa/K
    real(rk) :: mts_theta_iv = 0.0_rk, mts_alpha = 2.0_rk        !< Pa, -
    real(rk) :: mts_sigma0es = 0.0_rk, mts_g0es = 1.0_rk         !< Pa, -
    real(rk) :: mts_rate0es = 1.0e7_rk                           !< 1/s
    !> the MTS (Varshni) shear modulus: G = G0 - D / (exp(T0/T) - 1), G0 at 0 K
    real(rk) :: mts_d = 0.0_rk, mts_t0 = 0.0_rk                  !< Pa, K
    !> Preston-Tonks-Wallace (2003), dimensionless unless marked; flow stress 2 tau G
    real(rk) :: ptw_theta = 0.0_rk, ptw_p = 0.0_rk, ptw_s0 = 0.0_rk, ptw_sinf = 0.0_rk
    real(rk) :: ptw_kappa = 0.0_rk, ptw_gamma = 0.0_rk, ptw_y0 = 0.0_rk, ptw_yinf = 0.0_rk
    real(rk) :: ptw_y1 = 0.0_rk, ptw_y2 = 0.0_rk, ptw_beta = 0.0_rk
    real(rk) :: ptw_molar_mass = 0.0_rk                          !< kg/mol
    !> the PTW shear modulus G = G0 (1 - alpha T/T_m)
    real(rk) :: ptw_alpha = 0.0_rk                               !< -
    integer  :: melt_model = melt_constant
    !> Steinberg-Guinan melt: T_m = t_melt exp(2 a (1 - 1/eta)) eta^(2 (gamma0 - a - 1/3))
    real(rk) :: melt_a = 0.0_rk                                  !< -
    real(rk) :: t_melt = -1.0_rk               !< K
    real(rk) :: t_room = 294.0_rk              !< K
    real(rk) :: specific_heat = -1.0_rk        !< J/(kg K)
    real(rk) :: taylor_quinney = 0.9_rk        !< -, share of plastic work turned to heat
    !> heat also from the volumetric part: the artificial viscosity's work
    !> (the shock's entropy) and the Grueneisen term of adiabatic compression
    logical  :: shock_heating = .false.
    real(rk) :: initial_temperature = 294.0_rk !< K
    integer  :: fracture = fracture_none       !< how the material fractures
    real(rk) :: eps_f = -1.0_rk                !< -, critical equivalent plastic strain (fracture = 'plastic_strain')
    real(rk) :: jc_d1 = 0.0_rk, jc_d2 = 0.0_rk, jc_d3 = 0.0_rk, jc_d4 = 0.0_rk, jc_d5 = 0.0_rk
                                               !< -, Johnson-Cook (1985) damage constants (fracture = 'johnson_cook')
    real(rk) :: p_spall = 0.0_rk               !< Pa, spall strength: a mean stress below -p_spall fractures an element; 0 = no spall criterion
    real(rk) :: eps_erode = 0.0_rk             !< -, a fractured element is eroded when its accumulated equivalent
                                               !< (deviatoric) total strain passes this; 0 = never by strain
    integer  :: eroded = eroded_free_nodes     !< what an eroded element becomes (eroded_*)
    real(rk) :: eps_convert = 0.0_rk           !< -, eroded = 'particles': an element not fractured becomes a particle
                                               !< that keeps its strength when its accumulated equivalent total
                                               !< strain passes this; 0 = only fractured elements convert
    real(rk) :: artificial_stress = 0.3_rk     !< -, eps of the artificial stress of particles that keep their strength
                                               !< (Gray, Monaghan and Swift 2001), against SPH's tensile instability; 0 = none
  end type

  type :: part_cfg_t
    character(len=max_name_len) :: group = ''     !< gmsh physical volume group name
    character(len=max_name_len) :: material = ''  !< a &material name
    real(rk) :: velocity(3) = 0.0_rk              !< m/s
    real(rk) :: initial_temperature = -1.0_rk     !< K; below 0: the material's initial_temperature
  end type

  type :: boundary_cfg_t
    integer  :: kind = 0
    character(len=max_name_len) :: surface = ''   !< gmsh physical surface name (fixed, symmetry)
    real(rk) :: point(3) = 0.0_rk                 !< m, a point on the rigid wall
    real(rk) :: normal(3) = 0.0_rk                !< -, wall normal pointing towards the bodies
    integer  :: wall_type = wall_frictionless
    real(rk) :: friction = 0.0_rk                 !< -, Coulomb coefficient of a 'coulomb' wall
  end type

  type :: numerics_cfg_t
    logical  :: anti_locking = .true.   !< nodal-averaged volumetric strain (Bonet-Burton); .false. = plain tet
    integer  :: tet_formulation = tet_stabilised  !< with anti_locking: nodal, stabilised or stabilised_linear
    real(rk) :: stabilisation = 0.03_rk       !< -, beta0: weight of the element's own volume ratio near its nodes'
    real(rk) :: stabilisation_large = 0.1_rk  !< -, beta1: the weight at a large departure (geometric blend)
    real(rk) :: stabilisation_onset = 0.3_rk  !< -, |ln(Je/Jbar)| from which the weight is stabilisation_large
    real(rk) :: q_linear = 0.06_rk      !< -, linear artificial viscosity coefficient
    real(rk) :: q_quadratic = 1.5_rk    !< -, quadratic artificial viscosity coefficient
    real(rk) :: erode_dt_ratio = 0.1_rk !< -, an element of a material with eps_erode > 0 is eroded when its stable
                                        !< step falls below this fraction of the run's initial stable step; 0 = off
    logical  :: sph_viscosity_switch = .false. !< Balsara's switch on the particles' artificial viscosity
  end type

  type :: output_cfg_t
    character(len=max_path_len) :: directory = '.'   !< relative to the current directory
    character(len=max_name_len) :: case_name = ''    !< default: deck file name without .nml
    real(rk) :: dt_field = 0.0_rk      !< s, 0 = first and last state only
    real(rk) :: dt_history = 0.0_rk    !< s, 0 = every cycle
    real(rk) :: dt_checkpoint = 0.0_rk !< s, 0 = none (a wall_limit or signal stop still writes one)
    integer  :: checkpoint_keep = 2    !< -, newest checkpoints kept
  end type

  !> One contact interface (the seed paper's slideline algorithm): slave
  !> nodes kept out of master triangles.
  type :: contact_cfg_t
    character(len=max_name_len) :: master = ''   !< part (physical volume) or physical surface group name
    character(len=max_name_len) :: slave = ''    !< part (physical volume) or physical surface group name
    real(rk) :: friction = 0.0_rk                !< -, algorithmic friction coefficient f (0 = free sliding)
    integer  :: iterations = 50                  !< -, at most this many passes of the velocity matching a cycle
    real(rk) :: tolerance = 0.0_rk               !< m/s, stop once a pass changes no velocity by more; 0 = converged
                                                 !< (1e-10 of the first pass's largest change)
    logical  :: symmetric = .false.              !< also a pass with master and slave swapped
    logical  :: tracking = .true.                !< candidate lists kept between full searches (else a full search every cycle)
    logical  :: edges = .false.                  !< also edge-to-edge contact between the surfaces' feature edges
    logical  :: seams = .true.                   !< nodes in the seams of a dented master surface are found (theory.md 11)
    logical  :: sharp_edges = .true.             !< a node just outside a face beside a sharp convex edge is no contact of the other face (theory.md 11)
    logical  :: valleys = .false.                !< a node in a valley of the master surface is matched to both faces (theory.md 11)
    logical  :: voids = .false.                  !< the holes erosion leaves in its eroding parts close but never turn inside out (theory.md 12)
    integer  :: weights = contact_weights_area       !< shares of the master nodes: area (a moment balance) | distance (paper eq. 12)
    integer  :: initial_overlap = overlap_report     !< slave nodes behind the master at t = 0: report | move
  end type

  !> A gauge: the history of one mesh node (displacement, velocity), one
  !> element (pressure, stress, plastic strain, temperature, density) or a
  !> material point (both: it moves with the element it starts in).
  type :: gauge_cfg_t
    character(len=max_name_len) :: name = ''
    integer  :: node = 0                       !< mesh-file node tag (0: not this kind)
    integer  :: element = 0                    !< mesh-file element tag (0: not this kind)
    real(rk) :: point(3) = 0.0_rk              !< m, a point of the undeformed body
    logical  :: at_point = .false.             !< point was given
  end type

  type :: config_t
    character(len=max_path_len) :: deck_file = ''
    character(len=:), allocatable :: resolved_text   !< the fully resolved deck, for output attributes
    type(run_cfg_t) :: run
    type(mesh_cfg_t) :: mesh
    type(numerics_cfg_t) :: numerics
    type(output_cfg_t) :: output
    type(material_cfg_t), allocatable :: materials(:)
    type(part_cfg_t), allocatable :: parts(:)
    type(boundary_cfg_t), allocatable :: boundaries(:)
    type(contact_cfg_t), allocatable :: contacts(:)
    type(gauge_cfg_t), allocatable :: gauges(:)
  end type
end module udar_config
