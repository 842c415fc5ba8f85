!> The input deck reader: namelist groups -> config_t, with every problem in
!> the deck reported at once, each naming file, line, group and variable.
!>
!> Method. udar_nml_scan splits the deck into groups and assignments with line
!> numbers. Each group instance is then read with a real namelist READ from an
!> internal file; only if that fails (or the scan found something wrong in the
!> group) is every assignment read alone, so that the failing ones can be named
!> with their line and value. Values are then checked together (ranges, model
!> requirements, cross references) and derived values filled in, so that the
!> solver only reads bulk_modulus and shear_modulus.
!>
!> deck_write_resolved turns a config back into a deck that deck_read accepts
!> and that gives the same config: every variable, with its unit and a marker
!> for values the deck did not set.
!>
!> What is the same for every variable (its unit, its range, how its value is
!> written, compared with the default and checked for NaN) is done once, driven
!> by the variable table and by cfg_vals, which lists the values of a group in
!> table order; the checks spell out only the model logic.
module udar_deck
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use, intrinsic :: ieee_exceptions, only: ieee_status_type, ieee_get_status, ieee_set_status, &
       ieee_set_halting_mode, ieee_usual
  use, intrinsic :: iso_c_binding, only: c_char, c_ptr, c_null_char, c_associated
  use udar_kinds, only: rk, max_name_len, max_path_len
  use udar_config, only: config_t, gauge_cfg_t, run_cfg_t, mesh_cfg_t, material_cfg_t, part_cfg_t, &
       boundary_cfg_t, contact_cfg_t, numerics_cfg_t, output_cfg_t, eos_linear, eos_mie_gruneisen, tet_plain, tet_nodal, tet_stabilised, tet_stabilised_linear, &
       strength_none, strength_elastic, strength_perfectly_plastic, strength_linear_hardening, &
       strength_johnson_cook, strength_zerilli_armstrong, strength_steinberg_guinan, strength_mts, strength_ptw, &
       strength_steinberg_lund, shear_constant, &
       shear_steinberg_guinan, shear_mts, shear_ptw, melt_constant, melt_steinberg_guinan, bc_fixed, bc_symmetry, bc_rigid_wall, wall_frictionless, wall_sticking, &
       wall_coulomb, &
       jc_rate_total, jc_rate_plastic, contact_weights_distance, contact_weights_area, &
       overlap_report, overlap_move, fracture_none, fracture_plastic_strain, fracture_johnson_cook, &
       eroded_free_nodes, eroded_particles, &
       geometry_solid, geometry_axisymmetric, geometry_plane_strain
  use udar_input_errors, only: input_errors_t
  use udar_file_kind, only: not_regular_file
  use udar_log, only: log_warn
  use udar_nml_scan, only: nml_scan_t, nml_group_t, nml_scan_file, nml_location
  use udar_strings, only: itoa, r2s, to_lower, replace, shorten, dir_name, base_name
  implicit none
  private
  public :: deck_read, deck_write_resolved, deck_where

  character(len=*), parameter :: nl = achar(10)
  integer, parameter :: code_len = 32          !< length of the deck strings for coded choices
  real(rk), parameter :: rel_tol = 1.0e-6_rk   !< agreement asked of redundant elastic constants

  ! defaults, taken from udar_config so that they live in one place
  type(run_cfg_t), parameter :: run_dflt = run_cfg_t()
  type(material_cfg_t), parameter :: mat_dflt = material_cfg_t()
  integer, parameter :: title_len = len(run_dflt%title)

  ! ------------------------------------------------------------ the groups
  integer, parameter :: n_group_kinds = 9
  integer, parameter :: g_run = 1, g_mesh = 2, g_material = 3, g_part = 4, g_boundary = 5, &
                        g_contact = 6, g_numerics = 7, g_output = 8, g_gauge = 9    !< indices into the tables below
  character(len=8), parameter :: group_names(n_group_kinds) = [character(len=8) :: &
       'run', 'mesh', 'material', 'part', 'boundary', 'contact', 'numerics', 'output', 'gauge']
  logical, parameter :: group_once(n_group_kinds) = &
       [.true., .true., .false., .false., .false., .false., .true., .true., .false.]
  logical, parameter :: group_required(n_group_kinds) = &
       [.true., .true., .true., .true., .false., .false., .false., .false., .false.]
  character(len=80), parameter :: group_purpose(n_group_kinds) = [character(len=80) :: &
       'end time and time step control', 'the mesh file', 'material models', &
       'bodies: mesh volume, material, velocity', 'boundary conditions', &
       'contact interfaces: slave nodes kept out of master triangles (Yugov et al. 1998)', &
       'solver options', 'output files', 'histories at a node, an element or a material point']

  ! ------------------------------------------------- string forms of the codes
  character(len=20), parameter :: eos_words(2) = [character(len=20) :: 'linear', 'mie_gruneisen']
  integer, parameter :: eos_codes(2) = [eos_linear, eos_mie_gruneisen]
  character(len=20), parameter :: strength_words(10) = [character(len=20) :: 'none', 'elastic', &
       'perfectly_plastic', 'linear_hardening', 'johnson_cook', 'zerilli_armstrong', 'steinberg_guinan', 'mts', 'ptw', &
       'steinberg_lund']
  integer, parameter :: strength_codes(10) = [strength_none, strength_elastic, &
       strength_perfectly_plastic, strength_linear_hardening, strength_johnson_cook, &
       strength_zerilli_armstrong, strength_steinberg_guinan, strength_mts, strength_ptw, strength_steinberg_lund]
  character(len=20), parameter :: shear_words(4) = [character(len=20) :: 'constant', 'steinberg_guinan', 'mts', 'ptw']
  integer, parameter :: shear_codes(4) = [shear_constant, shear_steinberg_guinan, shear_mts, shear_ptw]
  character(len=20), parameter :: melt_words(2) = [character(len=20) :: 'constant', 'steinberg_guinan']
  integer, parameter :: melt_codes(2) = [melt_constant, melt_steinberg_guinan]
  character(len=20), parameter :: kind_words(3) = [character(len=20) :: 'fixed', 'symmetry', 'rigid_wall']
  integer, parameter :: kind_codes(3) = [bc_fixed, bc_symmetry, bc_rigid_wall]
  character(len=20), parameter :: wall_words(3) = [character(len=20) :: 'frictionless', 'sticking', 'coulomb']
  character(len=20), parameter :: rate_words(2) = [character(len=20) :: 'total', 'plastic']
  integer, parameter :: rate_codes(2) = [jc_rate_total, jc_rate_plastic]
  integer, parameter :: wall_codes(3) = [wall_frictionless, wall_sticking, wall_coulomb]
  character(len=20), parameter :: weights_words(2) = [character(len=20) :: 'distance', 'area']
  integer, parameter :: weights_codes(2) = [contact_weights_distance, contact_weights_area]
  character(len=20), parameter :: tet_words(4) = [character(len=20) :: 'plain', 'nodal', 'stabilised', &
       'stabilised_linear']
  integer, parameter :: tet_codes(4) = [tet_plain, tet_nodal, tet_stabilised, tet_stabilised_linear]
  character(len=20), parameter :: overlap_words(2) = [character(len=20) :: 'report', 'move']
  integer, parameter :: overlap_codes(2) = [overlap_report, overlap_move]
  character(len=20), parameter :: fracture_words(3) = [character(len=20) :: 'none', 'plastic_strain', &
       'johnson_cook']
  integer, parameter :: fracture_codes(3) = [fracture_none, fracture_plastic_strain, fracture_johnson_cook]
  character(len=20), parameter :: eroded_words(2) = [character(len=20) :: 'free_nodes', 'particles']
  integer, parameter :: eroded_codes(2) = [eroded_free_nodes, eroded_particles]
  character(len=20), parameter :: geometry_words(3) = [character(len=20) :: 'solid', 'axisymmetric', 'plane_strain']
  integer, parameter :: geometry_codes(3) = [geometry_solid, geometry_axisymmetric, geometry_plane_strain]

  ! ------------------------------------------------------ the variable table
  !> One deck variable: for unknown-name suggestions, read-failure
  !> explanations, the unit in the resolved deck and messages, and the range
  !> that the plain checks ask for (model-dependent rules are in check_*).
  type :: var_t
    character(len=8) :: grp = ''
    character(len=20) :: name = ''
    character :: typ = 'c'      !< r real, i integer, l logical, c character
    integer :: n = 1            !< number of components
    integer :: clen = 0         !< longest accepted string (typ c)
    character(len=8) :: unit = ''   !< SI unit; '-' dimensionless, '' strings and logicals
    character(len=14) :: rule = ''  !< the range a value must be in, as messages say it; '' none
  end type

  type(var_t), parameter :: vars(*) = [ &
       var_t('run', 'title', 'c', 1, title_len, '', ''), &
       var_t('run', 't_end', 'r', 1, 0, 's', '> 0'), &
       var_t('run', 'dt_safety', 'r', 1, 0, '-', 'in (0, 1]'), &
       var_t('run', 'dt_initial', 'r', 1, 0, 's', '>= 0'), &
       var_t('run', 'dt_max', 'r', 1, 0, 's', '> 0'), &
       var_t('run', 'max_cycles', 'i', 1, 0, '-', '>= 1'), &
       var_t('run', 'cycle_print', 'i', 1, 0, '-', '>= 1'), &
       var_t('run', 'energy_error_limit', 'r', 1, 0, '-', '> 0'), &
       var_t('run', 'wall_limit', 'r', 1, 0, 's', '>= 0'), &
       var_t('run', 'end_kinetic_fraction', 'r', 1, 0, '-', 'in [0, 1)'), &
       var_t('run', 'dt_warn_ratio', 'r', 1, 0, '-', 'in [0, 1)'), &
       var_t('run', 'rebalance_imbalance', 'r', 1, 0, '-', '>= 0'), &
       var_t('mesh', 'file', 'c', 1, max_path_len, '', ''), &
       var_t('mesh', 'scale', 'r', 1, 0, '-', '> 0'), &
       var_t('mesh', 'geometry', 'c', 1, code_len, '', ''), &
       var_t('material', 'name', 'c', 1, max_name_len, '', ''), &
       var_t('material', 'rho0', 'r', 1, 0, 'kg/m3', '> 0'), &
       var_t('material', 'eos', 'c', 1, code_len, '', ''), &
       var_t('material', 'bulk_modulus', 'r', 1, 0, 'Pa', '> 0'), &
       var_t('material', 'c0', 'r', 1, 0, 'm/s', '> 0'), &
       var_t('material', 's', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'gamma0', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'strength', 'c', 1, code_len, '', ''), &
       var_t('material', 'shear_modulus', 'r', 1, 0, 'Pa', '> 0'), &
       var_t('material', 'youngs_modulus', 'r', 1, 0, 'Pa', '> 0'), &
       var_t('material', 'poisson_ratio', 'r', 1, 0, '-', 'in (-1, 0.5)'), &
       var_t('material', 'yield_stress', 'r', 1, 0, 'Pa', '> 0'), &
       var_t('material', 'hardening_modulus', 'r', 1, 0, 'Pa', '>= 0'), &
       var_t('material', 'jc_a', 'r', 1, 0, 'Pa', '> 0'), &
       var_t('material', 'jc_b', 'r', 1, 0, 'Pa', '>= 0'), &
       var_t('material', 'jc_n', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'jc_c', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'jc_m', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'jc_rate0', 'r', 1, 0, '1/s', '> 0'), &
       var_t('material', 'jc_rate_form', 'c', 1, code_len, '', ''), &
       var_t('material', 'za_c0', 'r', 1, 0, 'Pa', '>= 0'), &
       var_t('material', 'za_c1', 'r', 1, 0, 'Pa', '>= 0'), &
       var_t('material', 'za_c2', 'r', 1, 0, 'Pa', '>= 0'), &
       var_t('material', 'za_c3', 'r', 1, 0, '1/K', '>= 0'), &
       var_t('material', 'za_c4', 'r', 1, 0, '1/K', '>= 0'), &
       var_t('material', 'za_c5', 'r', 1, 0, 'Pa', '>= 0'), &
       var_t('material', 'za_n', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'za_rate0', 'r', 1, 0, '1/s', '> 0'), &
       var_t('material', 'sg_y0', 'r', 1, 0, 'Pa', '> 0'), &
       var_t('material', 'sg_ymax', 'r', 1, 0, 'Pa', '> 0'), &
       var_t('material', 'sg_beta', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'sg_n', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'sg_eps_i', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'sl_yp', 'r', 1, 0, 'Pa', '> 0'), &
       var_t('material', 'sl_uk', 'r', 1, 0, 'J', '> 0'), &
       var_t('material', 'sl_c1', 'r', 1, 0, '1/s', '> 0'), &
       var_t('material', 'sl_c2', 'r', 1, 0, 'Pa s', '>= 0'), &
       var_t('material', 'shear_model', 'c', 1, code_len, '', ''), &
       var_t('material', 'sg_a', 'r', 1, 0, '1/Pa', '>= 0'), &
       var_t('material', 'sg_b', 'r', 1, 0, '1/K', '>= 0'), &
       var_t('material', 'sg_t0', 'r', 1, 0, 'K', '> 0'), &
       var_t('material', 'mts_sigma_a', 'r', 1, 0, 'Pa', '>= 0'), &
       var_t('material', 'mts_sigma_i', 'r', 1, 0, 'Pa', '>= 0'), &
       var_t('material', 'mts_g0i', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'mts_rate0i', 'r', 1, 0, '1/s', '> 0'), &
       var_t('material', 'mts_pi', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'mts_qi', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'mts_g0e', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'mts_rate0e', 'r', 1, 0, '1/s', '> 0'), &
       var_t('material', 'mts_pe', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'mts_qe', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'mts_kb3', 'r', 1, 0, 'Pa/K', '> 0'), &
       var_t('material', 'mts_a0', 'r', 1, 0, 'Pa', ''), &
       var_t('material', 'mts_a1', 'r', 1, 0, 'Pa', ''), &
       var_t('material', 'mts_a2', 'r', 1, 0, 'Pa s^1/2', ''), &
       var_t('material', 'mts_a3', 'r', 1, 0, 'Pa/K', ''), &
       var_t('material', 'mts_theta_iv', 'r', 1, 0, 'Pa', '>= 0'), &
       var_t('material', 'mts_alpha', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'mts_sigma0es', 'r', 1, 0, 'Pa', '> 0'), &
       var_t('material', 'mts_g0es', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'mts_rate0es', 'r', 1, 0, '1/s', '> 0'), &
       var_t('material', 'mts_d', 'r', 1, 0, 'Pa', '>= 0'), &
       var_t('material', 'mts_t0', 'r', 1, 0, 'K', '> 0'), &
       var_t('material', 'ptw_theta', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'ptw_p', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'ptw_s0', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'ptw_sinf', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'ptw_kappa', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'ptw_gamma', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'ptw_y0', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'ptw_yinf', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'ptw_y1', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'ptw_y2', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'ptw_beta', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'ptw_molar_mass', 'r', 1, 0, 'kg/mol', '> 0'), &
       var_t('material', 'ptw_alpha', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'melt_model', 'c', 1, code_len, '', ''), &
       var_t('material', 'melt_a', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 't_melt', 'r', 1, 0, 'K', '> 0'), &
       var_t('material', 't_room', 'r', 1, 0, 'K', '> 0'), &
       var_t('material', 'specific_heat', 'r', 1, 0, 'J/(kg K)', '> 0'), &
       var_t('material', 'taylor_quinney', 'r', 1, 0, '-', 'in [0, 1]'), &
       var_t('material', 'shock_heating', 'l', 1, 0, '', ''), &
       var_t('material', 'initial_temperature', 'r', 1, 0, 'K', '> 0'), &
       var_t('material', 'fracture', 'c', 1, code_len, '', ''), &
       var_t('material', 'eps_f', 'r', 1, 0, '-', '> 0'), &
       var_t('material', 'jc_d1', 'r', 1, 0, '-', ''), &
       var_t('material', 'jc_d2', 'r', 1, 0, '-', ''), &
       var_t('material', 'jc_d3', 'r', 1, 0, '-', ''), &
       var_t('material', 'jc_d4', 'r', 1, 0, '-', ''), &
       var_t('material', 'jc_d5', 'r', 1, 0, '-', ''), &
       var_t('material', 'p_spall', 'r', 1, 0, 'Pa', '>= 0'), &
       var_t('material', 'eps_erode', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'eroded', 'c', 1, code_len, '', ''), &
       var_t('material', 'eps_convert', 'r', 1, 0, '-', '>= 0'), &
       var_t('material', 'artificial_stress', 'r', 1, 0, '-', '>= 0'), &
       var_t('part', 'group', 'c', 1, max_name_len, '', ''), &
       var_t('part', 'material', 'c', 1, max_name_len, '', ''), &
       var_t('part', 'velocity', 'r', 3, 0, 'm/s', 'finite numbers'), &
       var_t('part', 'initial_temperature', 'r', 1, 0, 'K', '> 0'), &
       var_t('boundary', 'kind', 'c', 1, code_len, '', ''), &
       var_t('boundary', 'surface', 'c', 1, max_name_len, '', ''), &
       var_t('boundary', 'point', 'r', 3, 0, 'm', 'finite numbers'), &
       var_t('boundary', 'normal', 'r', 3, 0, '-', 'finite numbers'), &
       var_t('boundary', 'wall_type', 'c', 1, code_len, '', ''), &
       var_t('boundary', 'friction', 'r', 1, 0, '-', '>= 0'), &
       var_t('contact', 'master', 'c', 1, max_name_len, '', ''), &
       var_t('contact', 'slave', 'c', 1, max_name_len, '', ''), &
       var_t('contact', 'friction', 'r', 1, 0, '-', '>= 0'), &
       var_t('contact', 'iterations', 'i', 1, 0, '-', '>= 1'), &
       var_t('contact', 'tolerance', 'r', 1, 0, 'm/s', '>= 0'), &
       var_t('contact', 'symmetric', 'l', 1, 0, '', ''), &
       var_t('contact', 'tracking', 'l', 1, 0, '', ''), &
       var_t('contact', 'edges', 'l', 1, 0, '', ''), &
       var_t('contact', 'seams', 'l', 1, 0, '', ''), &
       var_t('contact', 'sharp_edges', 'l', 1, 0, '', ''), &
       var_t('contact', 'valleys', 'l', 1, 0, '', ''), &
       var_t('contact', 'voids', 'l', 1, 0, '', ''), &
       var_t('contact', 'weights', 'c', 1, code_len, '', ''), &
       var_t('contact', 'initial_overlap', 'c', 1, code_len, '', ''), &
       var_t('numerics', 'anti_locking', 'l', 1, 0, '', ''), &
       var_t('numerics', 'tet_formulation', 'c', 1, code_len, '', ''), &
       var_t('numerics', 'stabilisation', 'r', 1, 0, '-', 'in [0, 1)'), &
       var_t('numerics', 'stabilisation_large', 'r', 1, 0, '-', 'in [0, 1)'), &
       var_t('numerics', 'stabilisation_onset', 'r', 1, 0, '-', '> 0'), &
       var_t('numerics', 'q_linear', 'r', 1, 0, '-', '>= 0'), &
       var_t('numerics', 'q_quadratic', 'r', 1, 0, '-', '>= 0'), &
       var_t('numerics', 'erode_dt_ratio', 'r', 1, 0, '-', 'in [0, 1)'), &
       var_t('numerics', 'sph_viscosity_switch', 'l', 1, 0, '', ''), &
       var_t('output', 'directory', 'c', 1, max_path_len, '', ''), &
       var_t('output', 'case_name', 'c', 1, max_name_len, '', ''), &
       var_t('output', 'dt_field', 'r', 1, 0, 's', '>= 0'), &
       var_t('output', 'dt_history', 'r', 1, 0, 's', '>= 0'), &
       var_t('output', 'dt_checkpoint', 'r', 1, 0, 's', '>= 0'), &
       var_t('output', 'checkpoint_keep', 'i', 1, 0, '-', '>= 1'), &
       var_t('gauge', 'name', 'c', 1, max_name_len, '', ''), &
       var_t('gauge', 'node', 'i', 1, 0, '-', '>= 1'), &
       var_t('gauge', 'element', 'i', 1, 0, '-', '>= 1'), &
       var_t('gauge', 'point', 'r', 3, 0, 'm', 'finite numbers') ]

  !> The value of one variable, whatever its type: what lets one piece of code
  !> write, compare and check the variables of every group. Reals are made by
  !> val(), the others by the structure constructor.
  type :: val_t
    type(var_t) :: var                       !< its row of the table
    real(rk), allocatable :: r(:)            !< typ r: the n components
    integer :: i = 0                         !< typ i; for a coded choice its code
    logical :: l = .false.                   !< typ l
    character(len=:), allocatable :: c       !< typ c; for a coded choice its word
    character(len=160) :: choices = ''       !< coded choice: 'a | b', the resolved deck's unit
    character(len=160) :: from = ''           !< what a derived value is computed from
  end type

  interface val
    module procedure val_real, val_reals
  end interface val

  ! ----------------------------------------------------- working data types
  !> The namelist variables of one group instance while it is read. The coded
  !> choices stay strings here; they become codes after the read.
  type :: values_t
    type(run_cfg_t) :: run
    type(mesh_cfg_t) :: mesh
    type(material_cfg_t) :: mat
    type(part_cfg_t) :: part
    type(boundary_cfg_t) :: bnd
    type(contact_cfg_t) :: con
    type(numerics_cfg_t) :: num
    type(output_cfg_t) :: out
    type(gauge_cfg_t) :: gauge
    character(len=code_len) :: eos = 'linear'
    character(len=code_len) :: strength = 'elastic'
    character(len=code_len) :: kind = ''
    character(len=code_len) :: wall_type = 'frictionless'
    character(len=code_len) :: jc_rate_form = 'total'
    character(len=code_len) :: shear_model = 'constant'
    character(len=code_len) :: melt_model = 'constant'
    character(len=code_len) :: weights = 'area'
    character(len=code_len) :: initial_overlap = 'report'
    character(len=code_len) :: fracture = 'none'
    character(len=code_len) :: eroded = 'free_nodes'
    character(len=code_len) :: tet_formulation = 'stabilised'
    character(len=code_len) :: geometry = 'solid'
  end type

  !> One assignment as the deck wrote it.
  type :: asg_t
    character(len=32) :: base = ''
    character(len=:), allocatable :: value
    integer :: line = 0
    logical :: bad = .false.   !< could not be read: its variable is not validated further
  end type

  !> One group instance: where it is and what it assigned (also the record of
  !> which variables the deck set, for the '(default)' markers).
  type :: inst_t
    character(len=8) :: grp = ''
    integer :: number = 0      !< n-th instance of a repeatable group, 0 for once-only groups
    integer :: line = 0        !< line of '&name', 0 when the group is absent
    character(len=:), allocatable :: label
    type(asg_t), allocatable :: a(:)
  end type

  !> The instances of one group kind (a once-only group has one, also when absent).
  type :: inst_list_t
    type(inst_t), allocatable :: i(:)
  end type

  !> Assignment records of a whole deck: g(gk)%i(k) is the k-th &group_names(gk).
  type :: track_t
    type(inst_list_t) :: g(n_group_kinds)
  end type

  type :: diag_t
    integer :: line = 0
    character(len=:), allocatable :: text
  end type

  !> Messages of one deck_read, sorted by line before they are handed out.
  type :: ctx_t
    character(len=:), allocatable :: path
    type(nml_scan_t) :: lines                !< the scan's map of lines to files (includes)
    type(diag_t), allocatable :: d(:)
    integer :: n_dropped = 0                !< messages beyond max_messages
  end type
  integer, parameter :: max_messages = 100

  interface
    !> POSIX realpath(3): absolute, canonical form of an existing path.
    function c_realpath(path, resolved) bind(C, name='realpath') result(p)
      import :: c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      character(kind=c_char), intent(out) :: resolved(*)
      type(c_ptr) :: p
    end function c_realpath
  end interface

contains

  ! ======================================================================
  !  deck_read
  ! ======================================================================

  !> Read and check the deck at path. Problems are appended to errors (all of
  !> them, sorted by line); cfg is complete and resolved only when none were
  !> added, and then cfg%resolved_text holds the resolved deck.
  subroutine deck_read(path, cfg, errors)
    character(len=*), intent(in) :: path
    type(config_t), intent(out) :: cfg
    type(input_errors_t), intent(inout) :: errors
    type(ieee_status_type) :: fp_status

    ! a deck may hold 1e400 or NaN: these must become messages, not a
    ! floating-point trap (debug builds trap overflow and invalid)
    call ieee_get_status(fp_status)
    call ieee_set_halting_mode(ieee_usual, .false.)
    call read_deck(path, cfg, errors)
    call ieee_set_status(fp_status)
  end subroutine deck_read

  subroutine read_deck(path, cfg, errors)
    character(len=*), intent(in) :: path
    type(config_t), intent(inout) :: cfg
    type(input_errors_t), intent(inout) :: errors

    type(ctx_t) :: ctx
    type(nml_scan_t) :: scan
    type(track_t) :: tr
    type(values_t) :: v
    character(len=512) :: msg
    character(len=:), allocatable :: text
    character(len=code_len), allocatable :: eos_txt(:), str_txt(:), kind_txt(:), wall_txt(:), rate_txt(:), &
                                            weights_txt(:), overlap_txt(:), frac_txt(:), &
                                            eroded_txt(:), shear_txt(:), melt_txt(:)
    character(len=code_len) :: tet_txt, geometry_txt
    integer :: ios, k, j, ig, gk, first(n_group_kinds), cnt(n_group_kinds), nread(n_group_kinds)
    logical :: misspelled(n_group_kinds)

    cfg%deck_file = path
    tet_txt = v%tet_formulation     ! the default, when the deck has no &numerics
    geometry_txt = v%geometry
    ctx%path = trim(path)
    allocate(ctx%d(0))

    msg = ''
    call nml_scan_file(trim(path), scan, ios, msg)
    if (ios /= 0) then
      call errors%add(trim(path)//': cannot read the deck file: '//trim(msg))
      return
    end if

    if (allocated(scan%line_file)) then
      ctx%lines%files = scan%files
      ctx%lines%line_file = scan%line_file
      ctx%lines%line_orig = scan%line_orig
    end if
    do k = 1, scan%n_issues
      call report(ctx, scan%issues(k)%line, scan%issues(k)%text)
    end do

    ! which groups are there: unknown names, repeats, absences
    cnt = 0
    first = 0
    misspelled = .false.
    do ig = 1, scan%n_groups
      gk = group_index(scan%groups(ig)%name)
      if (gk == 0) then
        call report(ctx, scan%groups(ig)%start_line, 'unknown group &'//scan%groups(ig)%name// &
             group_suggestion(scan%groups(ig)%name))
        j = closest_word(scan%groups(ig)%name, group_names)
        if (j > 0) misspelled(j) = .true.
        cycle
      end if
      cnt(gk) = cnt(gk) + 1
      if (cnt(gk) == 1) then
        first(gk) = ig
      else if (group_once(gk)) then
        call report(ctx, scan%groups(ig)%start_line, '&'//trim(group_names(gk))// &
             ' appears again (first at line '//itoa(scan%groups(first(gk))%start_line)// &
             '): only one &'//trim(group_names(gk))//' group is allowed; this one is ignored')
      end if
    end do
    do gk = 1, n_group_kinds
      ! a misspelled group has been reported as such: not also as missing
      if (group_required(gk) .and. cnt(gk) == 0 .and. .not. misspelled(gk)) then
        if (group_once(gk)) then
          call report(ctx, 0, 'missing required group &'//trim(group_names(gk))// &
               ' ('//trim(group_purpose(gk))//')')
        else
          call report(ctx, 0, 'missing required group &'//trim(group_names(gk))// &
               ': at least one is needed ('//trim(group_purpose(gk))//')')
        end if
      end if
    end do

    allocate(cfg%materials(cnt(g_material)), cfg%parts(cnt(g_part)), &
             cfg%boundaries(cnt(g_boundary)), cfg%contacts(cnt(g_contact)), cfg%gauges(cnt(g_gauge)))
    allocate(eos_txt(cnt(g_material)), str_txt(cnt(g_material)), rate_txt(cnt(g_material)), &
             frac_txt(cnt(g_material)), eroded_txt(cnt(g_material)), shear_txt(cnt(g_material)), &
             melt_txt(cnt(g_material)), kind_txt(cnt(g_boundary)), &
             wall_txt(cnt(g_boundary)), weights_txt(cnt(g_contact)), overlap_txt(cnt(g_contact)))
    do gk = 1, n_group_kinds
      if (group_once(gk)) then
        ! the record of a once-only group exists also when the deck lacks it
        allocate(tr%g(gk)%i(1))
        call init_inst(tr%g(gk)%i(1), trim(group_names(gk)), 0, 0)
      else
        allocate(tr%g(gk)%i(cnt(gk)))
      end if
    end do

    ! read every group instance; reals must be finite before any other check
    nread = 0
    do ig = 1, scan%n_groups
      gk = group_index(scan%groups(ig)%name)
      if (gk == 0) cycle
      if (group_once(gk) .and. first(gk) /= ig) cycle
      nread(gk) = nread(gk) + 1
      k = nread(gk)
      v = values_t()
      call read_instance(ctx, scan%groups(ig), tr%g(gk)%i(k), merge(0, k, group_once(gk)), v)
      select case (gk)
      case (g_run)
        cfg%run = v%run
      case (g_mesh)
        cfg%mesh = v%mesh
        geometry_txt = v%geometry
      case (g_material)
        cfg%materials(k) = v%mat
        eos_txt(k) = v%eos
        str_txt(k) = v%strength
        rate_txt(k) = v%jc_rate_form
        shear_txt(k) = v%shear_model
        melt_txt(k) = v%melt_model
        frac_txt(k) = v%fracture
        eroded_txt(k) = v%eroded
      case (g_part)
        cfg%parts(k) = v%part
      case (g_boundary)
        cfg%boundaries(k) = v%bnd
        kind_txt(k) = v%kind
        wall_txt(k) = v%wall_type
      case (g_contact)
        cfg%contacts(k) = v%con
        weights_txt(k) = v%weights
        overlap_txt(k) = v%initial_overlap
      case (g_numerics)
        cfg%numerics = v%num
        tet_txt = v%tet_formulation
      case (g_output)
        cfg%output = v%out
      case (g_gauge)
        cfg%gauges(k) = v%gauge
      end select
      call check_finite(ctx, tr%g(gk)%i(k), cfg_vals(cfg, gk, k))
    end do

    ! check values, fill in derived ones
    associate (runs => tr%g(g_run)%i, meshes => tr%g(g_mesh)%i, mats => tr%g(g_material)%i, &
               parts => tr%g(g_part)%i, bnds => tr%g(g_boundary)%i, cons => tr%g(g_contact)%i)
      if (runs(1)%line > 0) call check_run(ctx, runs(1), cfg)
      if (meshes(1)%line > 0) call check_mesh(ctx, meshes(1), cfg%mesh, trim(path), geometry_txt)
      do k = 1, size(mats)
        call check_material(ctx, mats(k), cfg, k, eos_txt(k), str_txt(k), rate_txt(k), frac_txt(k), eroded_txt(k), &
                            shear_txt(k), melt_txt(k), &
                            mats(1:k-1))
      end do
      do k = 1, size(parts)
        call check_part(ctx, parts(k), cfg, k, parts(1:k-1))
      end do
      do k = 1, size(bnds)
        call check_boundary(ctx, bnds(k), cfg, k, kind_txt(k), wall_txt(k))
      end do
      do k = 1, size(cons)
        call check_contact(ctx, cons(k), cfg, k, weights_txt(k), overlap_txt(k))
      end do
    end associate
    call check_numerics(ctx, tr%g(g_numerics)%i(1), cfg, tet_txt)
    call check_output(ctx, tr%g(g_output)%i(1), cfg, trim(path))
    do k = 1, size(tr%g(g_gauge)%i)
      call check_gauge(ctx, tr%g(g_gauge)%i(k), cfg, k, tr%g(g_gauge)%i(1:k-1))
    end do

    ! hand the messages out in line order
    call sort_diags(ctx)
    do k = 1, size(ctx%d)
      call errors%add(ctx%d(k)%text)
    end do
    if (ctx%n_dropped > 0) call errors%add(ctx%path//': ... and '//itoa(ctx%n_dropped)// &
         ' more problems, not listed (is this a namelist deck?)')

    if (size(ctx%d) == 0 .and. ctx%n_dropped == 0) then
      call write_resolved(cfg, text, tr)
      call move_alloc(text, cfg%resolved_text)
    end if
  end subroutine read_deck

  !> Read one group instance into v (which holds the defaults on entry).
  subroutine read_instance(ctx, gr, inst, number, v)
    type(ctx_t), intent(inout) :: ctx
    type(nml_group_t), intent(in) :: gr
    type(inst_t), intent(inout) :: inst
    integer, intent(in) :: number
    type(values_t), intent(inout) :: v

    type(values_t) :: vtry
    character(len=512) :: msg, whole_msg
    character(len=:), allocatable :: grp, meant
    integer, allocatable :: slot(:)      ! gr%assigns(k) is inst%a(slot(k))
    logical :: diagnose
    integer :: k, j, iv, ios, nfail, clen

    grp = gr%name
    call init_inst(inst, grp, number, gr%start_line)
    inst%label = instance_label(gr)
    diagnose = .not. gr%clean

    ! what the scan alone tells: unknown names, empty values, repeats, long strings
    allocate(slot(gr%n_assign))
    do k = 1, gr%n_assign
      associate(a => gr%assigns(k))
        call inst_add(inst, a%base, a%value, a%line)
        slot(k) = size(inst%a)
        if (.not. a%ok) then
          ! the scan has already reported this assignment
          inst%a(slot(k))%bad = .true.
          diagnose = .true.
          cycle
        end if
        iv = var_index(grp, a%base)
        if (iv == 0) then
          call report(ctx, a%line, prefix(inst)//unknown_var_text(grp, a%base, meant))
          inst%a(slot(k))%bad = .true.
          diagnose = .true.
          ! the misspelled variable counts as given but unreadable, so that the
          ! checks do not also call it missing
          if (len(meant) > 0) call inst_add(inst, meant, a%value, a%line, bad=.true.)
          cycle
        end if
        if (len(a%value) == 0) then
          call report(ctx, a%line, prefix(inst)//a%name//' = : no value given')
          inst%a(slot(k))%bad = .true.
          diagnose = .true.
          cycle
        end if
        do j = 1, k - 1
          if (gr%assigns(j)%name == a%name) then
            call report(ctx, a%line, prefix(inst)//a%name//' = '//a%value// &
                 ' : assigned a second time (first at line '//itoa(gr%assigns(j)%line)// &
                 '); keep only one')
            exit
          end if
        end do
        if (vars(iv)%typ == 'c') then
          clen = quoted_length(a%value)
          if (clen > vars(iv)%clen) then
            call report(ctx, a%line, prefix(inst)//a%name//' = '//shorten(a%value)// &
                 ' : too long ('//itoa(clen)//' characters, at most '//itoa(vars(iv)%clen)//')')
            inst%a(slot(k))%bad = .true.
            diagnose = .true.
          end if
        else if (vars(iv)%typ == 'l' .and. .not. logical_text(a%value)) then
          ! gfortran reads "1" as a repeat count and fails with a message about that
          call report(ctx, a%line, prefix(inst)//a%name//' = '//shorten(a%value)// &
               ' : not a valid logical: use .true. or .false.')
          inst%a(slot(k))%bad = .true.
          diagnose = .true.
        end if
      end associate
    end do

    ! the real namelist read of the whole group
    whole_msg = ''
    if (.not. diagnose) then
      vtry = v
      call read_nml(grp, '&'//grp//' '//gr%body//' /', vtry, ios, whole_msg)
      if (ios == 0) then
        v = vtry
        return
      end if
    end if

    ! it failed or cannot succeed: read the assignments one by one, keeping the
    ! good ones, so that each bad one is named and the rest is still checked
    nfail = 0
    do k = 1, gr%n_assign
      if (inst%a(slot(k))%bad) cycle
      associate(a => gr%assigns(k))
        vtry = v
        msg = ''
        call read_nml(grp, '&'//grp//' '//a%name//' = '//a%value//' /', vtry, ios, msg)
        if (ios == 0) then
          v = vtry
        else
          nfail = nfail + 1
          inst%a(slot(k))%bad = .true.
          call report(ctx, a%line, prefix(inst)//a%name//' = '//shorten(a%value)//' : '// &
               read_failure_text(grp, a%name, a%base, a%value, trim(msg)))
          ! "x = 1 y 2": y was meant to be assigned; do not also call it missing
          meant = known_word_in(grp, a%value)
          if (len(meant) > 0) call inst_add(inst, meant, a%value, a%line, bad=.true.)
        end if
      end associate
    end do
    if (nfail == 0 .and. .not. diagnose) then
      ! every assignment reads alone, the group as a whole does not
      call report(ctx, gr%start_line, prefix(inst)//'the group cannot be read as a namelist: '// &
           trim(whole_msg))
      inst%a(:)%bad = .true.
    end if
  end subroutine read_instance

  !> Every real the deck set must be a finite number (namelist input accepts
  !> NaN, Inf and 1e400). Reported once here; later checks skip them.
  subroutine check_finite(ctx, inst, vals)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(inout) :: inst
    type(val_t), intent(in) :: vals(:)
    character(len=:), allocatable :: name
    integer :: j, k

    do j = 1, size(vals)
      if (vals(j)%var%typ /= 'r') cycle
      name = trim(vals(j)%var%name)
      if (all(ieee_is_finite(vals(j)%r)) .or. is_bad(inst, name)) cycle
      k = last_assign(inst, name)
      if (k == 0) cycle
      call report(ctx, inst%a(k)%line, prefix(inst)//name//' = '// &
           shorten(inst%a(k)%value)//' : not a finite number')
      inst%a(k)%bad = .true.
    end do
  end subroutine check_finite

  !> Namelist READ of text (one whole group, '&grp ... /') straight into the
  !> variables of v. A failed READ may have changed some of them: callers read
  !> into a scratch copy and keep it only if ios is 0.
  subroutine read_nml(grp, text, v, ios, msg)
    character(len=*), intent(in) :: grp, text
    type(values_t), intent(inout) :: v
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg

    ios = -1
    select case (grp)
    case ('run')
      associate(r => v%run)
        call run_nml(r%title, r%t_end, r%dt_safety, r%dt_initial, r%dt_max, r%max_cycles, &
                     r%cycle_print, r%energy_error_limit, r%wall_limit, r%end_kinetic_fraction, r%dt_warn_ratio, &
                     r%rebalance_imbalance)
      end associate
    case ('mesh')
      call mesh_nml(v%mesh%file, v%mesh%scale, v%geometry)
    case ('material')
      associate(m => v%mat)
        call material_nml(m%name, m%rho0, v%eos, m%bulk_modulus, m%c0, m%s, m%gamma0, &
             v%strength, m%shear_modulus, m%youngs_modulus, m%poisson_ratio, m%yield_stress, &
             m%hardening_modulus, m%jc_a, m%jc_b, m%jc_n, m%jc_c, m%jc_m, m%jc_rate0, v%jc_rate_form, &
             m%za_c0, m%za_c1, m%za_c2, m%za_c3, m%za_c4, m%za_c5, m%za_n, m%za_rate0, &
             m%sg_y0, m%sg_ymax, m%sg_beta, m%sg_n, m%sg_eps_i, m%sl_yp, m%sl_uk, m%sl_c1, m%sl_c2, v%shear_model, m%sg_a, m%sg_b, m%sg_t0, &
             m%mts_sigma_a, m%mts_sigma_i, m%mts_g0i, m%mts_rate0i, m%mts_pi, m%mts_qi, m%mts_g0e, m%mts_rate0e, m%mts_pe, m%mts_qe, &
             m%mts_kb3, m%mts_a0, m%mts_a1, m%mts_a2, m%mts_a3, m%mts_theta_iv, m%mts_alpha, m%mts_sigma0es, m%mts_g0es, m%mts_rate0es, m%mts_d, m%mts_t0, &
             m%ptw_theta, m%ptw_p, m%ptw_s0, m%ptw_sinf, m%ptw_kappa, m%ptw_gamma, m%ptw_y0, m%ptw_yinf, m%ptw_y1, m%ptw_y2, m%ptw_beta, m%ptw_molar_mass, m%ptw_alpha, &
             v%melt_model, m%melt_a, &
             m%t_melt, m%t_room, m%specific_heat, m%taylor_quinney, m%shock_heating, m%initial_temperature, &
             v%fracture, m%eps_f, m%jc_d1, m%jc_d2, m%jc_d3, m%jc_d4, m%jc_d5, m%p_spall, m%eps_erode, v%eroded, m%eps_convert, m%artificial_stress)
      end associate
    case ('part')
      call part_nml(v%part%group, v%part%material, v%part%velocity, v%part%initial_temperature)
    case ('boundary')
      call boundary_nml(v%kind, v%bnd%surface, v%bnd%point, v%bnd%normal, v%wall_type, v%bnd%friction)
    case ('contact')
      associate(c => v%con)
        call contact_nml(c%master, c%slave, c%friction, c%iterations, c%tolerance, c%symmetric, &
                         c%tracking, c%edges, c%seams, c%sharp_edges, c%valleys, c%voids, v%weights, v%initial_overlap)
      end associate
    case ('numerics')
      call numerics_nml(v%num%anti_locking, v%tet_formulation, v%num%stabilisation, v%num%stabilisation_large, &
                        v%num%stabilisation_onset, v%num%q_linear, v%num%q_quadratic, v%num%erode_dt_ratio, &
                        v%num%sph_viscosity_switch)
    case ('output')
      call output_nml(v%out%directory, v%out%case_name, v%out%dt_field, v%out%dt_history, v%out%dt_checkpoint, &
                      v%out%checkpoint_keep)
    case ('gauge')
      call gauge_nml(v%gauge%name, v%gauge%node, v%gauge%element, v%gauge%point)
    end select

  contains

    ! One reader per group: its dummy arguments are the namelist variables,
    ! named as in the deck.

    subroutine run_nml(title, t_end, dt_safety, dt_initial, dt_max, max_cycles, cycle_print, &
                       energy_error_limit, wall_limit, end_kinetic_fraction, dt_warn_ratio, rebalance_imbalance)
      character(len=*), intent(inout) :: title
      real(rk), intent(inout) :: t_end, dt_safety, dt_initial, dt_max, energy_error_limit, wall_limit, &
                                 end_kinetic_fraction, dt_warn_ratio, rebalance_imbalance
      integer, intent(inout) :: max_cycles, cycle_print
      namelist /run/ title, t_end, dt_safety, dt_initial, dt_max, max_cycles, cycle_print, &
                     energy_error_limit, wall_limit, end_kinetic_fraction, dt_warn_ratio, rebalance_imbalance
      read(text, nml=run, iostat=ios, iomsg=msg)
    end subroutine run_nml

    subroutine mesh_nml(file, scale, geometry)
      character(len=*), intent(inout) :: file, geometry
      real(rk), intent(inout) :: scale
      namelist /mesh/ file, scale, geometry
      read(text, nml=mesh, iostat=ios, iomsg=msg)
    end subroutine mesh_nml

    subroutine material_nml(name, rho0, eos, bulk_modulus, c0, s, gamma0, strength, shear_modulus, &
                            youngs_modulus, poisson_ratio, yield_stress, hardening_modulus, jc_a, &
                            jc_b, jc_n, jc_c, jc_m, jc_rate0, jc_rate_form, &
                            za_c0, za_c1, za_c2, za_c3, za_c4, za_c5, za_n, za_rate0, &
                            sg_y0, sg_ymax, sg_beta, sg_n, sg_eps_i, sl_yp, sl_uk, sl_c1, sl_c2, shear_model, sg_a, sg_b, sg_t0, &
                            mts_sigma_a, mts_sigma_i, mts_g0i, mts_rate0i, mts_pi, mts_qi, mts_g0e, mts_rate0e, mts_pe, mts_qe, &
                            mts_kb3, mts_a0, mts_a1, mts_a2, mts_a3, mts_theta_iv, mts_alpha, mts_sigma0es, mts_g0es, mts_rate0es, mts_d, mts_t0, &
                            ptw_theta, ptw_p, ptw_s0, ptw_sinf, ptw_kappa, ptw_gamma, ptw_y0, ptw_yinf, ptw_y1, ptw_y2, ptw_beta, ptw_molar_mass, ptw_alpha, &
                            melt_model, melt_a, t_melt, t_room, specific_heat, &
                            taylor_quinney, shock_heating, initial_temperature, fracture, eps_f, jc_d1, jc_d2, jc_d3, &
                            jc_d4, jc_d5, p_spall, eps_erode, eroded, eps_convert, artificial_stress)
      character(len=*), intent(inout) :: name, eos, strength, jc_rate_form, fracture, eroded, shear_model, melt_model
      real(rk), intent(inout) :: rho0, bulk_modulus, c0, s, gamma0, shear_modulus, youngs_modulus, &
           poisson_ratio, yield_stress, hardening_modulus, jc_a, jc_b, jc_n, jc_c, jc_m, jc_rate0, &
           za_c0, za_c1, za_c2, za_c3, za_c4, za_c5, za_n, za_rate0, sg_y0, sg_ymax, sg_beta, sg_n, sg_eps_i, &
           sl_yp, sl_uk, sl_c1, sl_c2, sg_a, sg_b, sg_t0, melt_a, mts_sigma_a, mts_sigma_i, mts_g0i, mts_rate0i, mts_pi, mts_qi, mts_g0e, mts_rate0e, mts_pe, mts_qe, &
           mts_kb3, mts_a0, mts_a1, mts_a2, mts_a3, mts_theta_iv, mts_alpha, mts_sigma0es, mts_g0es, mts_rate0es, mts_d, mts_t0, &
           ptw_theta, ptw_p, ptw_s0, ptw_sinf, ptw_kappa, ptw_gamma, ptw_y0, ptw_yinf, ptw_y1, ptw_y2, ptw_beta, &
           ptw_molar_mass, ptw_alpha, &
           t_melt, t_room, specific_heat, taylor_quinney, initial_temperature, eps_f, jc_d1, jc_d2, &
           jc_d3, jc_d4, jc_d5, p_spall, eps_erode, eps_convert, artificial_stress
      logical, intent(inout) :: shock_heating
      namelist /material/ name, rho0, eos, bulk_modulus, c0, s, gamma0, strength, shear_modulus, &
                          youngs_modulus, poisson_ratio, yield_stress, hardening_modulus, jc_a, &
                          jc_b, jc_n, jc_c, jc_m, jc_rate0, jc_rate_form, &
                          za_c0, za_c1, za_c2, za_c3, za_c4, za_c5, za_n, za_rate0, &
                          sg_y0, sg_ymax, sg_beta, sg_n, sg_eps_i, sl_yp, sl_uk, sl_c1, sl_c2, shear_model, sg_a, sg_b, sg_t0, &
                          mts_sigma_a, mts_sigma_i, mts_g0i, mts_rate0i, mts_pi, mts_qi, mts_g0e, mts_rate0e, mts_pe, mts_qe, &
                          mts_kb3, mts_a0, mts_a1, mts_a2, mts_a3, mts_theta_iv, mts_alpha, mts_sigma0es, mts_g0es, mts_rate0es, mts_d, mts_t0, &
                          ptw_theta, ptw_p, ptw_s0, ptw_sinf, ptw_kappa, ptw_gamma, ptw_y0, ptw_yinf, ptw_y1, ptw_y2, ptw_beta, ptw_molar_mass, ptw_alpha, &
                          melt_model, melt_a, t_melt, t_room, specific_heat, &
                          taylor_quinney, shock_heating, initial_temperature, fracture, eps_f, jc_d1, jc_d2, jc_d3, &
                          jc_d4, jc_d5, p_spall, eps_erode, eroded, eps_convert, artificial_stress
      read(text, nml=material, iostat=ios, iomsg=msg)
    end subroutine material_nml

    subroutine part_nml(group, material, velocity, initial_temperature)
      character(len=*), intent(inout) :: group, material
      real(rk), intent(inout) :: velocity(3), initial_temperature
      namelist /part/ group, material, velocity, initial_temperature
      read(text, nml=part, iostat=ios, iomsg=msg)
    end subroutine part_nml

    subroutine boundary_nml(kind, surface, point, normal, wall_type, friction)
      character(len=*), intent(inout) :: kind, surface, wall_type
      real(rk), intent(inout) :: friction
      real(rk), intent(inout) :: point(3), normal(3)
      namelist /boundary/ kind, surface, point, normal, wall_type, friction
      read(text, nml=boundary, iostat=ios, iomsg=msg)
    end subroutine boundary_nml

    subroutine contact_nml(master, slave, friction, iterations, tolerance, symmetric, tracking, edges, seams, &
                           sharp_edges, valleys, voids, weights, initial_overlap)
      character(len=*), intent(inout) :: master, slave, weights, initial_overlap
      real(rk), intent(inout) :: friction, tolerance
      integer, intent(inout) :: iterations
      logical, intent(inout) :: symmetric, tracking, edges, seams, sharp_edges, valleys, voids
      namelist /contact/ master, slave, friction, iterations, tolerance, symmetric, tracking, edges, seams, sharp_edges, &
                         valleys, voids, weights, initial_overlap
      read(text, nml=contact, iostat=ios, iomsg=msg)
    end subroutine contact_nml

    subroutine numerics_nml(anti_locking, tet_formulation, stabilisation, stabilisation_large, stabilisation_onset, &
                            q_linear, q_quadratic, erode_dt_ratio, sph_viscosity_switch)
      logical, intent(inout) :: anti_locking, sph_viscosity_switch
      character(len=*), intent(inout) :: tet_formulation
      real(rk), intent(inout) :: stabilisation, stabilisation_large, stabilisation_onset, q_linear, q_quadratic, &
                                 erode_dt_ratio
      namelist /numerics/ anti_locking, tet_formulation, stabilisation, stabilisation_large, stabilisation_onset, &
                          q_linear, q_quadratic, erode_dt_ratio, sph_viscosity_switch
      read(text, nml=numerics, iostat=ios, iomsg=msg)
    end subroutine numerics_nml

    subroutine output_nml(directory, case_name, dt_field, dt_history, dt_checkpoint, checkpoint_keep)
      character(len=*), intent(inout) :: directory, case_name
      real(rk), intent(inout) :: dt_field, dt_history, dt_checkpoint
      integer, intent(inout) :: checkpoint_keep
      namelist /output/ directory, case_name, dt_field, dt_history, dt_checkpoint, checkpoint_keep
      read(text, nml=output, iostat=ios, iomsg=msg)
    end subroutine output_nml

    subroutine gauge_nml(name, node, element, point)
      character(len=*), intent(inout) :: name
      integer, intent(inout) :: node, element
      real(rk), intent(inout) :: point(3)
      namelist /gauge/ name, node, element, point
      read(text, nml=gauge, iostat=ios, iomsg=msg)
    end subroutine gauge_nml

  end subroutine read_nml

  ! ======================================================================
  !  checks (of the k-th instance of a group in cfg, where there are several)
  ! ======================================================================

  !> A gauge: a name (letters, digits, '_'; unique), and exactly one of a
  !> node tag, an element tag or a point. The tags and the point are
  !> checked against the mesh when it is read (udar_setup).
  subroutine check_gauge(ctx, inst, cfg, k, earlier_inst)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(config_t), intent(inout) :: cfg
    integer, intent(in) :: k
    type(inst_t), intent(in) :: earlier_inst(:)    !< of gauges 1 .. k-1
    integer :: j, n_kinds
    associate(g => cfg%gauges(k))
      if (is_set(inst, 'node')) call check_ranges(ctx, inst, cfg_vals(cfg, g_gauge, k), 'node')
      if (is_set(inst, 'element')) call check_ranges(ctx, inst, cfg_vals(cfg, g_gauge, k), 'element')
      if (.not. is_bad(inst, 'name')) then
        if (len_trim(g%name) == 0) then
          call need(ctx, inst, 'name', .false., "the gauge's name, used in its history columns (gauge_<name>_vx)")
        else if (verify(trim(g%name), 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') > 0) then
          call complain(ctx, inst, 'name', 'letters, digits and _ only (it names history columns)')
        else
          j = findloc(cfg%gauges(1:k-1)%name == g%name, .true., 1)
          if (j > 0) call complain(ctx, inst, 'name', 'already the name of '//instance_ref(earlier_inst(j)))
        end if
      end if
      ! the kind by the values (a resolved deck lists them all: point 0, 0, 0
      ! beside a node is the default, not a second kind)
      g%at_point = g%node == 0 .and. g%element == 0
      n_kinds = count([g%node /= 0, g%element /= 0, is_set(inst, 'point') .and. any(g%point /= 0.0_rk)])
      if (n_kinds > 1 .or. (g%at_point .and. .not. is_set(inst, 'point'))) &
           call report(ctx, inst%line, prefix(inst)//'give exactly one of node (a mesh node tag), '// &
           'element (a mesh element tag) or point (x, y, z in m: a material point)')
    end associate
  end subroutine check_gauge

  subroutine check_run(ctx, inst, cfg)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(config_t), intent(in) :: cfg
    call check_ranges(ctx, inst, cfg_vals(cfg, g_run, 1))
    associate(r => cfg%run)
      if (positive(r%dt_initial) .and. positive(r%dt_max) .and. r%dt_initial > r%dt_max) &
           call complain(ctx, inst, 'dt_initial', 'larger than dt_max = '//r2s(r%dt_max)//' s')
    end associate
  end subroutine check_run

  !> Besides the ranges: the geometry is one of the words; the mesh file must exist; a relative name is taken
  !> from the deck's folder, and the absolute path is stored in m%file.
  subroutine check_mesh(ctx, inst, m, deck_path, geometry_txt)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(mesh_cfg_t), intent(inout) :: m
    character(len=*), intent(in) :: deck_path, geometry_txt
    character(len=:), allocatable :: f
    logical :: exists, ok

    ok = choice(ctx, inst, 'geometry', geometry_txt, geometry_words, geometry_codes, m%geometry)
    call need(ctx, inst, 'scale', positive(m%scale), '> 0 (e.g. 0.001 for a mesh in mm)')
    if (is_bad(inst, 'file')) return
    if (len_trim(m%file) == 0) then
      call need(ctx, inst, 'file', .false., "the gmsh mesh file, e.g. 'target.msh'")
      return
    end if
    f = trim(m%file)
    if (f(1:1) /= '/') f = dir_name(deck_path)//f
    inquire(file=f, exist=exists)
    if (.not. exists) then
      call complain(ctx, inst, 'file', "mesh file not found (looked for '"//f// &
           "'; a relative name is taken from the deck's folder)")
      return
    end if
    if (len(not_regular_file(f)) > 0) then
      call complain(ctx, inst, 'file', "'"//f//"' is "//not_regular_file(f)//', not a regular file')
      return
    end if
    m%file = absolute_path(f)
  end subroutine check_mesh

  !> Material models: ranges, what each EOS / strength / fracture model needs,
  !> parameters set for a model that is not selected, and the derived elastic
  !> moduli.
  subroutine check_material(ctx, inst, cfg, k, eos_txt, str_txt, rate_txt, frac_txt, eroded_txt, shear_txt, melt_txt, &
                            earlier_inst)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(config_t), intent(inout) :: cfg
    integer, intent(in) :: k
    character(len=*), intent(in) :: eos_txt, str_txt, rate_txt, frac_txt, eroded_txt, shear_txt, melt_txt
    type(inst_t), intent(in) :: earlier_inst(:)    !< of materials 1 .. k-1

    logical :: eos_ok, str_ok, rate_ok, frac_ok, e_set, nu_set, en_ok, plastic, elastic_needed, jc_fracture, modelled
    real(rk) :: k_en, g_en, k_mg
    character(len=:), allocatable :: sname, fname
    integer :: j

    associate(m => cfg%materials(k))
      ! name: present and unique (names are compared without regard to case)
      if (.not. is_bad(inst, 'name')) then
        if (len_trim(m%name) == 0) then
          call need(ctx, inst, 'name', .false., 'a name that &part groups refer to')
        else
          j = findloc(to_lower(cfg%materials(1:k-1)%name) == to_lower(m%name), .true., 1)
          if (j > 0) call complain(ctx, inst, 'name', 'the name is already used by '// &
               instance_ref(earlier_inst(j)))
        end if
      end if

      call ranges('rho0')

      eos_ok = choice(ctx, inst, 'eos', eos_txt, eos_words, eos_codes, m%eos)
      str_ok = choice(ctx, inst, 'strength', str_txt, strength_words, strength_codes, m%strength)
      rate_ok = choice(ctx, inst, 'jc_rate_form', rate_txt, rate_words, rate_codes, m%jc_rate_form)
      frac_ok = choice(ctx, inst, 'fracture', frac_txt, fracture_words, fracture_codes, m%fracture)
      jc_fracture = frac_ok .and. m%fracture == fracture_johnson_cook

      ! Young's modulus and Poisson's ratio: optional, but only as a pair
      ! (an unreadable value counts as given: it has been reported already)
      e_set = m%youngs_modulus /= mat_dflt%youngs_modulus .or. is_bad(inst, 'youngs_modulus')
      nu_set = m%poisson_ratio /= mat_dflt%poisson_ratio .or. is_bad(inst, 'poisson_ratio')
      if (e_set) call ranges('youngs_modulus')
      if (nu_set) call ranges('poisson_ratio')
      if (e_set .and. .not. nu_set .and. .not. is_bad(inst, 'poisson_ratio')) &
           call complain(ctx, inst, 'youngs_modulus', &
           'poisson_ratio is not set: give both (or bulk_modulus and shear_modulus directly)')
      if (nu_set .and. .not. e_set .and. .not. is_bad(inst, 'youngs_modulus')) &
           call complain(ctx, inst, 'poisson_ratio', &
           'youngs_modulus is not set: give both (or bulk_modulus and shear_modulus directly)')
      en_ok = e_set .and. nu_set .and. positive(m%youngs_modulus) .and. &
              inside(m%poisson_ratio, -1.0_rk, 0.5_rk) .and. &
              .not. is_bad(inst, 'youngs_modulus') .and. .not. is_bad(inst, 'poisson_ratio')
      k_en = 0
      g_en = 0
      if (en_ok) then
        k_en = m%youngs_modulus / (3 * (1 - 2 * m%poisson_ratio))
        g_en = m%youngs_modulus / (2 * (1 + m%poisson_ratio))
      end if

      ! equation of state
      if (eos_ok) then
        select case (m%eos)
        case (eos_linear)
          if (m%bulk_modulus /= mat_dflt%bulk_modulus) then
            call ranges('bulk_modulus')
            call agree('bulk_modulus', m%bulk_modulus, k_en, 'E/(3(1-2nu))')
          else if (en_ok) then
            m%bulk_modulus = k_en
          else if (.not. (e_set .or. nu_set)) then
            call need(ctx, inst, 'bulk_modulus', .false., &
                 "> 0 for eos = 'linear' (or give youngs_modulus and poisson_ratio)")
          end if
        case (eos_mie_gruneisen)
          call need(ctx, inst, 'c0', positive(m%c0), "> 0 for eos = 'mie_gruneisen'")
          call ranges('s gamma0')
          ! the EOS fixes the bulk modulus: K0 = rho0 c0^2
          if (positive(m%c0) .and. positive(m%rho0)) then
            k_mg = m%rho0 * m%c0**2
            if (m%bulk_modulus /= mat_dflt%bulk_modulus) then
              if (differs(m%bulk_modulus, k_mg) .and. .not. is_bad(inst, 'bulk_modulus')) &
                   call complain(ctx, inst, 'bulk_modulus', "eos = 'mie_gruneisen' sets it to "// &
                   'rho0*c0**2 = '//r2s(k_mg)//' Pa: leave bulk_modulus out')
            else
              m%bulk_modulus = k_mg
            end if
            ! E and nu set only the shear modulus here; a bulk modulus they imply
            ! far from rho0*c0**2 is likely a mistake in one of them: say so
            if (en_ok .and. abs(k_en - k_mg) > 0.01_rk * k_mg) call log_warn( &
                 nml_location(ctx%lines, inst%line, ctx%path)//': '//prefix(inst)//'youngs_modulus and poisson_ratio imply a bulk '// &
                 'modulus E/(3(1-2nu)) = '//sig4(k_en)//' Pa, '//pct(k_en / k_mg - 1)// &
                 " from the rho0*c0**2 = "//r2s(k_mg)//" Pa that eos = 'mie_gruneisen' uses; "// &
                 'they set only the shear modulus')
          end if
        end select
        if (m%eos /= eos_mie_gruneisen) call not_used('c0 s gamma0', "eos = 'mie_gruneisen'")
      end if

      ! shear modulus
      elastic_needed = str_ok .and. m%strength /= strength_none
      if (m%shear_modulus /= mat_dflt%shear_modulus) then
        if (str_ok .and. m%strength == strength_none) then
          call need(ctx, inst, 'shear_modulus', nonneg(m%shear_modulus), '>= 0')
        else
          call ranges('shear_modulus')
        end if
        call agree('shear_modulus', m%shear_modulus, g_en, 'E/(2(1+nu))')
      else if (en_ok) then
        m%shear_modulus = g_en
      else if (elastic_needed .and. .not. (e_set .or. nu_set)) then
        call need(ctx, inst, 'shear_modulus', .false., "> 0 for strength = '"// &
             trim(str_txt)//"' (or give youngs_modulus and poisson_ratio)")
      else if (str_ok .and. m%strength == strength_none) then
        m%shear_modulus = 0     ! a fluid: the solver reads 0
      end if

      ! plasticity
      if (str_ok) then
        sname = "strength = '"//trim(strength_words(findloc(strength_codes, m%strength, 1)))//"'"
        plastic = m%strength == strength_perfectly_plastic .or. m%strength == strength_linear_hardening
        if (plastic) then
          call need(ctx, inst, 'yield_stress', positive(m%yield_stress), '> 0 for '//sname)
        else if (m%strength == strength_johnson_cook) then
          call not_used('yield_stress', &
               "'perfectly_plastic' or 'linear_hardening' (Johnson-Cook takes jc_a)")
        else
          call not_used('yield_stress', &
               "strength = 'perfectly_plastic', 'linear_hardening' or 'johnson_cook' (jc_a)")
        end if
        if (m%strength == strength_linear_hardening) then
          call ranges('hardening_modulus')
        else
          call not_used('hardening_modulus', "strength = 'linear_hardening'")
        end if
        if (m%strength == strength_johnson_cook) then
          call need(ctx, inst, 'jc_a', positive(m%jc_a), '> 0 for '//sname)
          call ranges('jc_b jc_n jc_c jc_m jc_rate0')
          call need(ctx, inst, 'specific_heat', positive(m%specific_heat), &
               '> 0 for '//sname//' (thermal softening)')
          if (.not. is_bad(inst, 't_room')) then
            call need(ctx, inst, 't_melt', positive(m%t_melt) .and. positive(m%t_room) .and. &
                 m%t_melt > m%t_room, '> t_room = '//r2s(m%t_room)//' K for '//sname)
          end if
        else
          call not_used('jc_a jc_b jc_n jc_c jc_m', "strength = 'johnson_cook'")
          ! the reference rate also scales the rate term of Johnson-Cook fracture
          if (jc_fracture) then
            call ranges('jc_rate0')
          else
            call not_used('jc_rate0', "strength = 'johnson_cook' or fracture = 'johnson_cook'")
          end if
        end if
        if (m%strength == strength_zerilli_armstrong) then
          call ranges('za_c0 za_c1 za_c2 za_c3 za_c4 za_c5 za_n za_rate0')
          if (.not. (m%za_c0 + m%za_c1 > 0 .or. m%za_c2 > 0 .or. m%za_c5 > 0)) &
               call report(ctx, inst%line, prefix(inst)//'za_c0, za_c1, za_c2 and za_c5 are all 0: '//sname// &
               ' needs a flow stress (za_c0 + za_c1 > 0 or za_c2 > 0; Zerilli and Armstrong 1987)')
          call need(ctx, inst, 'specific_heat', positive(m%specific_heat), &
               '> 0 for '//sname//' (the temperature of its thermal term)')
        else
          call not_used('za_c0 za_c1 za_c2 za_c3 za_c4 za_c5 za_n za_rate0', "strength = 'zerilli_armstrong'")
        end if
        if (m%strength == strength_steinberg_guinan .or. m%strength == strength_steinberg_lund) then
          call need(ctx, inst, 'sg_y0', positive(m%sg_y0), '> 0 for '//sname)
          if (.not. is_bad(inst, 'sg_y0')) call need(ctx, inst, 'sg_ymax', positive(m%sg_ymax) .and. &
               m%sg_ymax >= m%sg_y0, '>= sg_y0 = '//r2s(m%sg_y0)//' Pa for '//sname)
          call ranges('sg_beta sg_n sg_eps_i')
        else
          call not_used('sg_y0 sg_ymax sg_beta sg_n sg_eps_i', "strength = 'steinberg_guinan' or 'steinberg_lund'")
        end if
        if (m%strength == strength_steinberg_lund) then
          call need(ctx, inst, 'sl_yp', positive(m%sl_yp), '> 0 for '//sname//' (the Peierls stress)')
          call need(ctx, inst, 'sl_uk', positive(m%sl_uk), '> 0 for '//sname// &
               ' (the kink-pair energy in J: 0.31 eV = 4.967e-20 J)')
          call need(ctx, inst, 'sl_c1', positive(m%sl_c1), '> 0 for '//sname)
          call ranges('sl_c2')
          call need(ctx, inst, 'specific_heat', positive(m%specific_heat), &
               '> 0 for '//sname//' (the temperature of its activation term)')
        else
          call not_used('sl_yp sl_uk sl_c1 sl_c2', "strength = 'steinberg_lund'")
        end if
        if (m%strength == strength_mts) then
          call ranges('mts_sigma_a mts_sigma_i mts_g0i mts_rate0i mts_pi mts_qi mts_g0e mts_rate0e mts_pe mts_qe '// &
                      'mts_theta_iv mts_alpha mts_g0es mts_rate0es')
          call need(ctx, inst, 'mts_kb3', positive(m%mts_kb3), "> 0 for "//sname// &
               ' (Boltzmann constant over b^3, e.g. 0.823e6 Pa/K for copper)')
          call need(ctx, inst, 'mts_sigma0es', positive(m%mts_sigma0es), '> 0 for '//sname// &
               ' (the saturation threshold stress at 0 K)')
          call need(ctx, inst, 'specific_heat', positive(m%specific_heat), &
               '> 0 for '//sname//' (the temperature of its activation terms)')
        else
          call not_used('mts_sigma_a mts_sigma_i mts_g0i mts_rate0i mts_pi mts_qi mts_g0e mts_rate0e mts_pe mts_qe '// &
                        'mts_kb3 mts_a0 mts_a1 mts_a2 mts_a3 mts_theta_iv mts_alpha mts_sigma0es mts_g0es mts_rate0es', &
                        "strength = 'mts'")
        end if
      end if
      if (str_ok) then
        if (m%strength == strength_ptw) then
          call ranges('ptw_theta ptw_p ptw_sinf ptw_y0 ptw_yinf ptw_y1 ptw_y2 ptw_beta')
          call need(ctx, inst, 'ptw_s0', positive(m%ptw_s0), '> 0 for '//sname//' (the saturation stress at 0 K / G)')
          call need(ctx, inst, 'ptw_kappa', positive(m%ptw_kappa), '> 0 for '//sname)
          call need(ctx, inst, 'ptw_gamma', positive(m%ptw_gamma), '> 0 for '//sname)
          call need(ctx, inst, 'ptw_molar_mass', positive(m%ptw_molar_mass), '> 0 for '//sname// &
               ' (kg/mol: 0.06355 for copper)')
          call need(ctx, inst, 't_melt', positive(m%t_melt), '> 0 for '//sname//' (its homologous temperature)')
          call need(ctx, inst, 'specific_heat', positive(m%specific_heat), &
               '> 0 for '//sname//' (the temperature)')
        else
          call not_used('ptw_theta ptw_p ptw_s0 ptw_sinf ptw_kappa ptw_gamma ptw_y0 ptw_yinf ptw_y1 ptw_y2 ptw_beta '// &
                        'ptw_molar_mass', "strength = 'ptw'")
        end if
      end if
      modelled = str_ok .and. (m%strength == strength_zerilli_armstrong .or. m%strength == strength_steinberg_guinan &
                               .or. m%strength == strength_mts .or. m%strength == strength_ptw &
                               .or. m%strength == strength_steinberg_lund)
      ! the shear modulus and melt models serve the models that take the state
      if (choice(ctx, inst, 'shear_model', shear_txt, shear_words, shear_codes, m%shear_model)) then
        if (m%shear_model /= shear_constant .and. str_ok .and. .not. modelled) call complain(ctx, inst, 'shear_model', &
             "'"//trim(shear_txt)//"' serves strength = 'zerilli_armstrong', 'steinberg_guinan', 'steinberg_lund', "// &
             "'mts' or 'ptw' "// &
             '(the other models take shear_modulus)')
        if (m%shear_model == shear_mts) then
          call need(ctx, inst, 'mts_t0', positive(m%mts_t0), "> 0 for shear_model = 'mts' (G = G0 - D/(exp(T0/T) - 1))")
          call ranges('mts_d')
        else
          call not_used('mts_d mts_t0', "shear_model = 'mts'")
        end if
        if (m%shear_model == shear_ptw) then
          call ranges('ptw_alpha')
          if (.not. positive(m%t_melt) .and. m%strength /= strength_ptw) &
               call need(ctx, inst, 't_melt', .false., "> 0 for shear_model = 'ptw'")
        else
          call not_used('ptw_alpha', "shear_model = 'ptw'")
        end if
        if (m%shear_model == shear_steinberg_guinan) then
          call ranges('sg_a sg_b sg_t0')
          if (positive(m%sg_b)) call need(ctx, inst, 'specific_heat', positive(m%specific_heat), &
               "> 0 for shear_model = 'steinberg_guinan' with sg_b > 0 (the temperature)")
        else
          call not_used('sg_a sg_b sg_t0', "shear_model = 'steinberg_guinan'")
        end if
      end if
      if (choice(ctx, inst, 'melt_model', melt_txt, melt_words, melt_codes, m%melt_model)) then
        if (m%melt_model == melt_steinberg_guinan) then
          if (str_ok .and. .not. modelled) call complain(ctx, inst, 'melt_model', "'steinberg_guinan' serves "// &
               "strength = 'zerilli_armstrong', 'steinberg_guinan', 'steinberg_lund', 'mts' or 'ptw' "// &
               '(Johnson-Cook takes t_melt)')
          call need(ctx, inst, 't_melt', positive(m%t_melt), "> 0 for melt_model = 'steinberg_guinan' "// &
               '(the melt temperature at rho0)')
          if (eos_ok .and. m%eos /= eos_mie_gruneisen) call complain(ctx, inst, 'melt_model', &
               "'steinberg_guinan' takes gamma0 of eos = 'mie_gruneisen'")
          call ranges('melt_a')
        else
          call not_used('melt_a', "melt_model = 'steinberg_guinan'")
        end if
      end if

      ! thermal data (also used for output when the model does not need it)
      if (m%specific_heat /= mat_dflt%specific_heat) call ranges('specific_heat')
      if (m%t_melt /= mat_dflt%t_melt) call ranges('t_melt')
      call ranges('t_room taylor_quinney initial_temperature')
      if (m%shock_heating) call need(ctx, inst, 'specific_heat', positive(m%specific_heat), &
           '> 0 for shock_heating (the temperature it heats)')
      ! the body starts at room temperature unless the deck says otherwise
      if (.not. is_set(inst, 'initial_temperature') .and. positive(m%t_room)) &
           m%initial_temperature = m%t_room

      ! fracture and erosion (the criteria themselves act in the element driver)
      if (frac_ok) then
        fname = "fracture = '"//code_word(m%fracture, fracture_words, fracture_codes)//"'"
        select case (m%fracture)
        case (fracture_plastic_strain)
          call need(ctx, inst, 'eps_f', positive(m%eps_f), '> 0 for '//fname)
          call not_used('jc_d1 jc_d2 jc_d3 jc_d4 jc_d5', "fracture = 'johnson_cook'")
        case (fracture_johnson_cook)
          if (m%eps_f /= mat_dflt%eps_f) call complain(ctx, inst, 'eps_f', 'set, but '//fname// &
               ' computes the fracture strain from jc_d1 .. jc_d5: remove the line')
          call jc_d12()
          ! D5 needs the homologous temperature: t_melt (a Johnson-Cook
          ! strength has asked for it already)
          if (m%jc_d5 /= 0 .and. .not. is_bad(inst, 'jc_d5') .and. .not. is_bad(inst, 't_room') .and. &
              str_ok .and. m%strength /= strength_johnson_cook) &
               call need(ctx, inst, 't_melt', positive(m%t_melt) .and. positive(m%t_room) .and. &
               m%t_melt > m%t_room, '> t_room = '//r2s(m%t_room)//' K for '//fname// &
               ' with jc_d5 /= 0')
        case default
          call not_used('eps_f', "fracture = 'plastic_strain'")
          call not_used('jc_d1 jc_d2 jc_d3 jc_d4 jc_d5', "fracture = 'johnson_cook'")
        end select
      end if
      call ranges('p_spall eps_erode')
      if (frac_ok .and. m%fracture == fracture_none .and. m%p_spall == 0 .and. positive(m%eps_erode) &
          .and. .not. is_bad(inst, 'p_spall')) &
           call complain(ctx, inst, 'eps_erode', 'erosion needs a fracture criterion: set fracture or p_spall')
      if (choice(ctx, inst, 'eroded', eroded_txt, eroded_words, eroded_codes, m%eroded)) then
        if (m%eroded == eroded_particles .and. .not. positive(m%eps_erode) .and. .not. is_bad(inst, 'eps_erode')) &
             call complain(ctx, inst, 'eroded', "'particles' is what eroded elements become: set eps_erode > 0 "// &
             '(the material does not erode)')
      end if
      call ranges('eps_convert')
      if (positive(m%eps_convert) .and. m%eroded /= eroded_particles .and. .not. is_bad(inst, 'eroded')) &
           call complain(ctx, inst, 'eps_convert', "set, but only eroded = 'particles' converts elements: "// &
           "add eroded = 'particles' or remove the line")
      call ranges('artificial_stress')
      if (.not. positive(m%eps_convert) .and. .not. is_bad(inst, 'eps_convert')) &
           call not_used('artificial_stress', 'particles that keep their strength (eps_convert > 0)')
      ! 2D: none (its default off). With it the OFHC Taylor bar converting
      ! gained 16 % of its energy by 17 us in plane strain and blew up
      ! axisymmetric; without it -0.5 % at 80 us (validation.md 4zh)
      if (cfg%mesh%geometry /= geometry_solid .and. positive(m%eps_convert)) then
        if (is_set(inst, 'artificial_stress') .and. positive(m%artificial_stress)) &
             call complain(ctx, inst, 'artificial_stress', 'is 3D only: in 2D (geometry = '''// &
             trim(merge('axisymmetric', 'plane_strain', cfg%mesh%geometry == geometry_axisymmetric))// &
             ''') it makes converting decks gain energy (doc/validation.md 4zh); set 0 or leave it out (2D default 0)')
        m%artificial_stress = 0.0_rk
      end if
    end associate

  contains

    !> The table's range for each listed variable, at the current values.
    subroutine ranges(names)
      character(len=*), intent(in) :: names
      call check_ranges(ctx, inst, cfg_vals(cfg, g_material, k), names)
    end subroutine ranges

    !> The listed variables should not be set without the model used_by.
    subroutine not_used(names, used_by)
      character(len=*), intent(in) :: names, used_by
      call unused(ctx, inst, cfg_vals(cfg, g_material, k), default_vals(g_material), names, used_by)
    end subroutine not_used

    !> A modulus given directly must agree with the one from youngs_modulus
    !> and poisson_ratio (x_en, by formula) when those are given too.
    subroutine agree(name, x, x_en, formula)
      character(len=*), intent(in) :: name, formula
      real(rk), intent(in) :: x, x_en
      if (.not. (en_ok .and. positive(x))) return
      if (differs(x, x_en)) call complain(ctx, inst, name, 'disagrees with youngs_modulus and '// &
           'poisson_ratio, which give '//formula//' = '//r2s(x_en)//' Pa: give one or the other')
    end subroutine agree

    !> Johnson-Cook fracture: D1 + D2, the fracture strain at zero stress
    !> triaxiality (reference rate, room temperature), must be positive.
    subroutine jc_d12()
      character(len=*), parameter :: why = "> 0 for fracture = 'johnson_cook' (the fracture strain " // &
           'at zero stress triaxiality)'
      character(len=:), allocatable :: at
      associate(m => cfg%materials(k))
        if (is_bad(inst, 'jc_d1') .or. is_bad(inst, 'jc_d2')) return
        if (m%jc_d1 + m%jc_d2 > 0) return
        if (is_set(inst, 'jc_d1') .or. is_set(inst, 'jc_d2')) then
          ! at the later of the two assignments
          at = 'jc_d2'
          if (last_assign(inst, 'jc_d1') > last_assign(inst, 'jc_d2')) at = 'jc_d1'
          call complain(ctx, inst, at, 'jc_d1 + jc_d2 = '//r2s(m%jc_d1 + m%jc_d2)//': must be '//why)
        else
          call report(ctx, inst%line, prefix(inst)//'jc_d1 and jc_d2 are required but not set: give '// &
               'jc_d1 + jc_d2 '//why)
        end if
      end associate
    end subroutine jc_d12

  end subroutine check_material

  !> A part names a mesh volume group and a defined material.
  subroutine check_part(ctx, inst, cfg, k, earlier_inst)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(config_t), intent(inout) :: cfg
    integer, intent(in) :: k
    type(inst_t), intent(in) :: earlier_inst(:)    !< of parts 1 .. k-1
    character(len=:), allocatable :: names
    integer :: j, found

    associate(p => cfg%parts(k), mats => cfg%materials)
      if (.not. is_bad(inst, 'group')) then
        if (len_trim(p%group) == 0) then
          call need(ctx, inst, 'group', .false., 'the name of a physical volume group in the mesh')
        else
          j = findloc(cfg%parts(1:k-1)%group == p%group, .true., 1)
          if (j > 0) call complain(ctx, inst, 'group', 'the same mesh group is already used by '// &
               instance_ref(earlier_inst(j)))
        end if
      end if

      if (.not. is_bad(inst, 'material')) then
        names = ''
        do j = 1, size(mats)
          if (len_trim(mats(j)%name) == 0) cycle
          if (len(names) > 0) names = names//', '
          names = names//"'"//trim(mats(j)%name)//"'"
        end do
        if (len(names) == 0) names = 'none'
        if (len_trim(p%material) == 0) then
          call need(ctx, inst, 'material', .false., 'the name of a &material (defined: '// &
               names//')')
        else
          found = findloc(to_lower(mats%name) == to_lower(p%material), .true., 1)
          if (found == 0) then
            call complain(ctx, inst, 'material', 'no &material of that name (defined: '//names//')')
          else
            p%material = mats(found)%name    ! the material's own spelling
            if (.not. is_set(inst, 'initial_temperature')) p%initial_temperature = mats(found)%initial_temperature
          end if
        end if
      end if
    end associate

    call check_ranges(ctx, inst, cfg_vals(cfg, g_part, k), 'velocity')
    ! a temperature of its own, or its material's (set above)
    if (is_set(inst, 'initial_temperature')) &
         call check_ranges(ctx, inst, cfg_vals(cfg, g_part, k), 'initial_temperature')
  end subroutine check_part

  subroutine check_boundary(ctx, inst, cfg, k, kind_txt, wall_txt)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(config_t), intent(inout) :: cfg
    integer, intent(in) :: k
    character(len=*), intent(in) :: kind_txt, wall_txt
    logical :: kind_ok, wall_ok
    real(rk) :: nrm

    associate(b => cfg%boundaries(k))
      if (len_trim(kind_txt) == 0 .and. .not. is_bad(inst, 'kind')) then
        call need(ctx, inst, 'kind', .false., 'one of '//quoted_list(kind_words))
        kind_ok = .false.
      else
        kind_ok = choice(ctx, inst, 'kind', kind_txt, kind_words, kind_codes, b%kind)
      end if
      wall_ok = choice(ctx, inst, 'wall_type', wall_txt, wall_words, wall_codes, b%wall_type)
      call check_ranges(ctx, inst, cfg_vals(cfg, g_boundary, k))
      if (.not. kind_ok) return

      select case (b%kind)
      case (bc_fixed, bc_symmetry)
        if (len_trim(b%surface) == 0) call need(ctx, inst, 'surface', .false., &
             "the name of a physical surface group in the mesh, for kind = '"//trim(kind_txt)//"'")
        if (wall_ok) call unused(ctx, inst, cfg_vals(cfg, g_boundary, k), default_vals(g_boundary), &
             'wall_type friction', "kind = 'rigid_wall'")
      case (bc_rigid_wall)
        if (wall_ok .and. b%wall_type /= wall_coulomb) call unused(ctx, inst, cfg_vals(cfg, g_boundary, k), &
             default_vals(g_boundary), 'friction', "wall_type = 'coulomb'")
        if (all(ieee_is_finite(b%normal)) .and. .not. is_bad(inst, 'normal')) then
          nrm = norm2(b%normal)
          if (nrm > 0) then
            ! normalise; a vector already of unit length is kept bit for bit
            if (abs(nrm - 1) > 8 * epsilon(1.0_rk)) b%normal = b%normal / nrm
          else
            call need(ctx, inst, 'normal', .false., &
                 "a non-zero vector for kind = 'rigid_wall' (pointing towards the bodies)")
          end if
        end if
      end select
    end associate
  end subroutine check_boundary

  !> A contact interface names a master and a different slave (whether the
  !> names are in the mesh is checked once the mesh is read).
  subroutine check_contact(ctx, inst, cfg, k, weights_txt, overlap_txt)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(config_t), intent(inout) :: cfg
    integer, intent(in) :: k
    character(len=*), intent(in) :: weights_txt, overlap_txt
    logical :: ok
    character(len=*), parameter :: what = 'the name of a part (physical volume group) or of a '// &
         'physical surface group in the mesh'

    associate(c => cfg%contacts(k))
      if (len_trim(c%master) == 0) call need(ctx, inst, 'master', .false., what)
      if (len_trim(c%slave) == 0) call need(ctx, inst, 'slave', .false., what)
      if (len_trim(c%master) > 0 .and. to_lower(c%slave) == to_lower(c%master) .and. c%symmetric) &
           call complain(ctx, inst, 'symmetric', 'has no meaning for self-contact (slave = master): leave it out')
      if (len_trim(c%master) > 0 .and. to_lower(c%slave) == to_lower(c%master) .and. c%edges) &
           call complain(ctx, inst, 'edges', 'is not available for self-contact (slave = master) yet: leave it out')
      ok = choice(ctx, inst, 'weights', weights_txt, weights_words, weights_codes, c%weights)
      ok = choice(ctx, inst, 'initial_overlap', overlap_txt, overlap_words, overlap_codes, c%initial_overlap)
      call check_ranges(ctx, inst, cfg_vals(cfg, g_contact, k))
    end associate
  end subroutine check_contact

  subroutine check_numerics(ctx, inst, cfg, tet_txt)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(config_t), intent(inout) :: cfg
    character(len=*), intent(in) :: tet_txt
    logical :: ok
    ok = choice(ctx, inst, 'tet_formulation', tet_txt, tet_words, tet_codes, cfg%numerics%tet_formulation)
    call check_ranges(ctx, inst, cfg_vals(cfg, g_numerics, 1))
    ! the share grows with the departure from the nodes (theory.md 8.1)
    call need(ctx, inst, 'stabilisation', cfg%numerics%stabilisation <= cfg%numerics%stabilisation_large, &
              'at most stabilisation_large = '//r2s(cfg%numerics%stabilisation_large))
  end subroutine check_numerics

  subroutine check_output(ctx, inst, cfg, deck_path)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(config_t), intent(inout) :: cfg
    character(len=*), intent(in) :: deck_path
    call check_ranges(ctx, inst, cfg_vals(cfg, g_output, 1))
    associate(o => cfg%output)
      if (len_trim(o%directory) == 0) call need(ctx, inst, 'directory', .false., &
           "a folder name ('.' = the current folder)")
      if (len_trim(o%case_name) == 0 .and. .not. is_set(inst, 'case_name')) then
        o%case_name = stem_of(deck_path)
      else if (len_trim(o%case_name) == 0) then
        call need(ctx, inst, 'case_name', .false., 'a non-empty name for the output files')
      else if (.not. is_bad(inst, 'case_name')) then
        ! the outputs are <directory>/<case_name>.h5 etc.: a separator or a dot
        ! folder would put them somewhere else
        if (index(o%case_name, '/') > 0) then
          call complain(ctx, inst, 'case_name', "a case name is a file name, without '/': "// &
               'give folders in directory')
        else if (trim(o%case_name) == '.' .or. trim(o%case_name) == '..') then
          call complain(ctx, inst, 'case_name', "'.' and '..' are folders, not file names")
        end if
      end if
      if (.not. is_bad(inst, 'case_name')) call no_control_chars('case_name', o%case_name)
      if (.not. is_bad(inst, 'directory')) call no_control_chars('directory', o%directory)
    end associate

  contains

    !> A name for the file system may hold anything but control characters
    !> (a newline or an escape in a file name breaks logs and scripts).
    subroutine no_control_chars(name, str)
      character(len=*), intent(in) :: name, str
      integer :: i, code
      do i = 1, len_trim(str)
        code = iachar(str(i:i))
        if (code < 32 .or. code == 127) then
          call complain(ctx, inst, name, 'contains a control character (code '//itoa(code)// &
               ') at position '//itoa(i)//': names may hold any printable character')
          return
        end if
      end do
    end subroutine no_control_chars

  end subroutine check_output

  ! ---------------------------------------------------------- check helpers

  !> Report name unless ok: "name = value : must be RULE (UNIT)" where the deck
  !> set it, "name is required: RULE (UNIT)" where it did not (the unit is the
  !> table's). Silent for variables that could not be read (already reported).
  subroutine need(ctx, inst, name, ok, rule)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    character(len=*), intent(in) :: name
    logical, intent(in) :: ok
    character(len=*), intent(in) :: rule
    character(len=:), allocatable :: u, unit
    integer :: k
    if (ok .or. is_bad(inst, name)) return
    unit = trim(vars(var_index(inst%grp, name))%unit)
    u = ''
    if (len(unit) > 0 .and. unit /= '-') u = ' ('//unit//')'
    k = last_assign(inst, name)
    if (k > 0) then
      call report(ctx, inst%a(k)%line, prefix(inst)//name//' = '//shorten(inst%a(k)%value)// &
           ' : must be '//rule//u)
    else
      call report(ctx, inst%line, prefix(inst)//name//' is required but not set: give '// &
           rule//u)
    end if
  end subroutine need

  !> need() with the table's range for each value that has one and whose
  !> variable is in names (blank-separated; every one if names is absent), in
  !> table order. vals: inst's values, from cfg_vals.
  subroutine check_ranges(ctx, inst, vals, names)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(val_t), intent(in) :: vals(:)
    character(len=*), intent(in), optional :: names
    integer :: j

    do j = 1, size(vals)
      associate(var => vals(j)%var)
        if (len_trim(var%rule) == 0) cycle
        if (present(names)) then
          if (.not. in_list(trim(var%name), names)) cycle
        end if
        call need(ctx, inst, trim(var%name), meets(var%rule, vals(j)), trim(var%rule))
      end associate
    end do
  end subroutine check_ranges

  !> Whether x is in the range rule (one of the table's).
  logical function meets(rule, x) result(ok)
    character(len=*), intent(in) :: rule
    type(val_t), intent(in) :: x
    select case (rule)
    case ('> 0')
      ok = all(positive(x%r))
    case ('>= 0')
      ok = all(nonneg(x%r))
    case ('>= 1')
      ok = x%i >= 1
    case ('in (0, 1]')
      ok = all(inside(x%r, 0.0_rk, 1.0_rk) .or. x%r == 1)
    case ('in (-1, 0.5)')
      ok = all(inside(x%r, -1.0_rk, 0.5_rk))
    case ('in [0, 1]')
      ok = all(nonneg(x%r) .and. x%r <= 1)
    case ('in [0, 1)')
      ok = all(nonneg(x%r) .and. x%r < 1)
    case ('finite numbers')
      ok = all(ieee_is_finite(x%r))
    case default
      ok = .true.
    end select
  end function meets

  !> Report a problem with variable name: at its assignment if the deck made one.
  subroutine complain(ctx, inst, name, what)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    character(len=*), intent(in) :: name, what
    integer :: k
    if (is_bad(inst, name)) return
    k = last_assign(inst, name)
    if (k > 0) then
      call report(ctx, inst%a(k)%line, prefix(inst)//name//' = '//shorten(inst%a(k)%value)// &
           ' : '//what)
    else
      call report(ctx, inst%line, prefix(inst)//name//': '//what)
    end if
  end subroutine complain

  !> Parameters set (not at their defaults dvals) for a model that is not
  !> selected: likely a forgotten switch. names as for check_ranges.
  subroutine unused(ctx, inst, vals, dvals, names, used_by)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(val_t), intent(in) :: vals(:), dvals(:)
    character(len=*), intent(in) :: names, used_by
    integer :: j

    do j = 1, size(vals)
      if (in_list(trim(vals(j)%var%name), names) .and. .not. same_value(vals(j), dvals(j))) &
           call complain(ctx, inst, trim(vals(j)%var%name), 'set, but only used with '// &
           used_by//': select that model or remove the line')
    end do
  end subroutine unused

  !> Map a choice string to its code; report unknown strings with the choices.
  logical function choice(ctx, inst, name, txt, words, codes, code) result(ok)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    character(len=*), intent(in) :: name, txt
    character(len=*), intent(in) :: words(:)
    integer, intent(in) :: codes(:)
    integer, intent(inout) :: code
    character(len=:), allocatable :: w
    integer :: j
    ok = .false.
    if (is_bad(inst, name)) return
    w = to_lower(trim(adjustl(txt)))
    do j = 1, size(words)
      if (w == trim(words(j))) then
        code = codes(j)
        ok = .true.
        return
      end if
    end do
    call complain(ctx, inst, name, 'unknown choice; valid: '//quoted_list(words)// &
         suggestion(w, words, "'", "'"))
  end function choice

  ! (finite first: no ordered comparison with NaN)
  elemental logical function positive(x)
    real(rk), intent(in) :: x
    positive = .false.
    if (ieee_is_finite(x)) positive = x > 0
  end function positive

  elemental logical function nonneg(x)
    real(rk), intent(in) :: x
    nonneg = .false.
    if (ieee_is_finite(x)) nonneg = x >= 0
  end function nonneg

  !> x in the open interval (lo, hi).
  elemental logical function inside(x, lo, hi)
    real(rk), intent(in) :: x, lo, hi
    inside = .false.
    if (ieee_is_finite(x)) inside = x > lo .and. x < hi
  end function inside

  !> Relative disagreement of redundant constants (NaN counts as disagreeing).
  pure logical function differs(a, b)
    real(rk), intent(in) :: a, b
    differs = .true.
    if (ieee_is_finite(a) .and. ieee_is_finite(b)) differs = abs(a - b) > rel_tol * max(abs(a), abs(b))
  end function differs

  ! ======================================================================
  !  resolved deck
  ! ======================================================================

  !> The resolved deck of cfg: every variable of every group, in namelist
  !> syntax that deck_read accepts and that gives the same configuration.
  !> '(default)' marks values equal to the built-in default (deck_read's own
  !> copy in cfg%resolved_text marks what the deck did not set instead).
  subroutine deck_write_resolved(cfg, text)
    type(config_t), intent(in) :: cfg
    character(len=:), allocatable, intent(out) :: text
    type(ieee_status_type) :: fp_status
    call ieee_get_status(fp_status)
    call ieee_set_halting_mode(ieee_usual, .false.)
    call write_resolved(cfg, text)
    call ieee_set_status(fp_status)
  end subroutine deck_write_resolved

  subroutine write_resolved(cfg, text, tr)
    type(config_t), intent(in) :: cfg
    character(len=:), allocatable, intent(out) :: text
    type(track_t), intent(in), optional :: tr
    type(inst_t) :: untracked
    integer :: gk, k

    text = '! udar resolved input deck'//nl
    if (len_trim(cfg%deck_file) > 0) text = text//'! from: '//trim(cfg%deck_file)//nl
    if (present(tr)) then
      text = text//'! (default) = not set in the deck, (derived) = computed from other values,'//nl
      text = text//'! (not set) = not given and not needed'//nl
    else
      text = text//'! (default) = the built-in default value'//nl
    end if

    do gk = 1, n_group_kinds
      do k = 1, n_instances(cfg, gk)
        if (present(tr)) then
          call put_group(text, gk, cfg_vals(cfg, gk, k), default_vals(gk), tr%g(gk)%i(k), .true.)
        else
          call put_group(text, gk, cfg_vals(cfg, gk, k), default_vals(gk), untracked, .false.)
        end if
      end do
    end do
  end subroutine write_resolved

  !> One group instance: "&group", a line per variable, "/". vals and dvals
  !> (the defaults) are in table order; inst is only read when tracked.
  subroutine put_group(text, gk, vals, dvals, inst, tracked)
    character(len=:), allocatable, intent(inout) :: text
    integer, intent(in) :: gk
    type(val_t), intent(in) :: vals(:), dvals(:)
    type(inst_t), intent(in) :: inst
    logical, intent(in) :: tracked
    character(len=:), allocatable :: unit
    integer :: j

    text = text//nl//'&'//trim(group_names(gk))//nl
    do j = 1, size(vals)
      unit = trim(vals(j)%var%unit)
      if (len_trim(vals(j)%choices) > 0) unit = trim(vals(j)%choices)   ! coded: the words
      call put(text, inst, tracked, trim(vals(j)%var%name), value_text(vals(j)), unit, &
               same_value(vals(j), dvals(j)), trim(vals(j)%from))
    end do
    text = text//'/'//nl
  end subroutine put_group

  !> One "  name = value   ! unit (marker)" line.
  subroutine put(text, inst, tracked, name, value, unit, at_default, derived_from)
    character(len=:), allocatable, intent(inout) :: text
    type(inst_t), intent(in) :: inst
    logical, intent(in) :: tracked
    character(len=*), intent(in) :: name, value, unit
    logical, intent(in) :: at_default
    character(len=*), intent(in) :: derived_from    !< '' if not known
    character(len=:), allocatable :: line, note
    integer, parameter :: comment_col = 40

    note = ''
    if (tracked) then
      if (.not. is_set(inst, name)) then
        if (at_default .and. value == '-1.0') then
          note = '(not set)'          ! -1 is the "not given" value in udar_config
        else if (at_default) then
          note = '(default)'
        else if (len(derived_from) > 0) then
          note = '(derived: '//derived_from//')'
        else
          note = '(derived)'
        end if
      end if
    else if (at_default) then
      note = '(default)'
    end if
    line = '  '//name//' = '//value
    if (len(unit) > 0 .or. len(note) > 0) then
      if (len(line) < comment_col) line = line//repeat(' ', comment_col - len(line))
      line = line//' !'
      if (len(unit) > 0) line = line//' '//unit
      if (len(note) > 0) line = line//' '//note
    end if
    text = text//line//nl
  end subroutine put

  ! ======================================================================
  !  the values of a group, in table order
  ! ======================================================================

  !> Number of instances of group kind gk in cfg.
  pure integer function n_instances(cfg, gk) result(n)
    type(config_t), intent(in) :: cfg
    integer, intent(in) :: gk
    n = merge(1, 0, group_once(gk))
    select case (gk)
    case (g_material)
      if (allocated(cfg%materials)) n = size(cfg%materials)
    case (g_part)
      if (allocated(cfg%parts)) n = size(cfg%parts)
    case (g_boundary)
      if (allocated(cfg%boundaries)) n = size(cfg%boundaries)
    case (g_contact)
      if (allocated(cfg%contacts)) n = size(cfg%contacts)
    case (g_gauge)
      if (allocated(cfg%gauges)) n = size(cfg%gauges)
    end select
  end function n_instances

  !> The values of the k-th instance of group kind gk in cfg, in table order
  !> and each with its table row: the one place, besides the namelist readers,
  !> that names every variable.
  function cfg_vals(cfg, gk, k) result(vals)
    type(config_t), intent(in) :: cfg
    integer, intent(in) :: gk, k
    type(val_t), allocatable :: vals(:)
    character(len=:), allocatable :: k_from

    select case (gk)
    case (g_run)
      associate(r => cfg%run)
        vals = [val_t(c=r%title), val(r%t_end), val(r%dt_safety), val(r%dt_initial), &
                val(r%dt_max), val_t(i=r%max_cycles), val_t(i=r%cycle_print), &
                val(r%energy_error_limit), val(r%wall_limit), val(r%end_kinetic_fraction), val(r%dt_warn_ratio), &
                val(r%rebalance_imbalance)]
      end associate
    case (g_mesh)
      vals = [val_t(c=cfg%mesh%file), val(cfg%mesh%scale), choice_val(cfg%mesh%geometry, geometry_words, geometry_codes)]
    case (g_material)
      associate(m => cfg%materials(k))
        ! where a bulk modulus the deck did not give comes from
        k_from = 'youngs_modulus, poisson_ratio'
        if (m%eos == eos_mie_gruneisen) then
          k_from = 'rho0*c0**2'
          ! E and nu then set only the shear modulus: show the K they imply
          if (m%youngs_modulus > 0 .and. m%poisson_ratio > -1 .and. m%poisson_ratio < 0.5_rk) &
               k_from = k_from//'; youngs_modulus, poisson_ratio (used for the shear modulus only) imply '// &
               'E/(3(1-2nu)) = '//sig4(m%youngs_modulus / (3 * (1 - 2 * m%poisson_ratio)))
        end if
        vals = [val_t(c=m%name), val(m%rho0), choice_val(m%eos, eos_words, eos_codes), &
                val(m%bulk_modulus, k_from), val(m%c0), val(m%s), val(m%gamma0), &
                choice_val(m%strength, strength_words, strength_codes), &
                val(m%shear_modulus, 'youngs_modulus, poisson_ratio'), val(m%youngs_modulus), &
                val(m%poisson_ratio), val(m%yield_stress), val(m%hardening_modulus), val(m%jc_a), &
                val(m%jc_b), val(m%jc_n), val(m%jc_c), val(m%jc_m), val(m%jc_rate0), &
                choice_val(m%jc_rate_form, rate_words, rate_codes), &
                val(m%za_c0), val(m%za_c1), val(m%za_c2), val(m%za_c3), val(m%za_c4), val(m%za_c5), val(m%za_n), &
                val(m%za_rate0), val(m%sg_y0), val(m%sg_ymax), val(m%sg_beta), val(m%sg_n), val(m%sg_eps_i), &
                val(m%sl_yp), val(m%sl_uk), val(m%sl_c1), val(m%sl_c2), choice_val(m%shear_model, shear_words, shear_codes), val(m%sg_a), val(m%sg_b), val(m%sg_t0), &
                val(m%mts_sigma_a), val(m%mts_sigma_i), val(m%mts_g0i), val(m%mts_rate0i), val(m%mts_pi), val(m%mts_qi), val(m%mts_g0e), &
                val(m%mts_rate0e), val(m%mts_pe), val(m%mts_qe), val(m%mts_kb3), val(m%mts_a0), val(m%mts_a1), val(m%mts_a2), &
                val(m%mts_a3), val(m%mts_theta_iv), val(m%mts_alpha), val(m%mts_sigma0es), val(m%mts_g0es), val(m%mts_rate0es), val(m%mts_d), val(m%mts_t0), &
                val(m%ptw_theta), val(m%ptw_p), val(m%ptw_s0), val(m%ptw_sinf), val(m%ptw_kappa), val(m%ptw_gamma), val(m%ptw_y0), &
                val(m%ptw_yinf), val(m%ptw_y1), val(m%ptw_y2), val(m%ptw_beta), val(m%ptw_molar_mass), val(m%ptw_alpha), &
                choice_val(m%melt_model, melt_words, melt_codes), val(m%melt_a), val(m%t_melt), val(m%t_room), val(m%specific_heat), val(m%taylor_quinney), val_t(l=m%shock_heating), &
                val(m%initial_temperature, 't_room'), choice_val(m%fracture, fracture_words, fracture_codes), &
                val(m%eps_f), val(m%jc_d1), val(m%jc_d2), val(m%jc_d3), val(m%jc_d4), val(m%jc_d5), &
                val(m%p_spall), val(m%eps_erode), choice_val(m%eroded, eroded_words, eroded_codes), val(m%eps_convert), &
                val(m%artificial_stress)]
      end associate
    case (g_part)
      associate(p => cfg%parts(k))
        vals = [val_t(c=p%group), val_t(c=p%material), val(p%velocity), &
                val(p%initial_temperature, "the material's initial_temperature")]
      end associate
    case (g_boundary)
      associate(b => cfg%boundaries(k))
        vals = [choice_val(b%kind, kind_words, kind_codes), val_t(c=b%surface), val(b%point), &
                val(b%normal), choice_val(b%wall_type, wall_words, wall_codes), val(b%friction)]
      end associate
    case (g_contact)
      associate(c => cfg%contacts(k))
        vals = [val_t(c=c%master), val_t(c=c%slave), val(c%friction), val_t(i=c%iterations), &
                val(c%tolerance), val_t(l=c%symmetric), val_t(l=c%tracking), val_t(l=c%edges), val_t(l=c%seams), &
                val_t(l=c%sharp_edges), val_t(l=c%valleys), val_t(l=c%voids), &
                choice_val(c%weights, weights_words, weights_codes), &
                choice_val(c%initial_overlap, overlap_words, overlap_codes)]
      end associate
    case (g_numerics)
      vals = [val_t(l=cfg%numerics%anti_locking), &
              choice_val(cfg%numerics%tet_formulation, tet_words, tet_codes), val(cfg%numerics%stabilisation), &
              val(cfg%numerics%stabilisation_large), val(cfg%numerics%stabilisation_onset), val(cfg%numerics%q_linear), &
              val(cfg%numerics%q_quadratic), val(cfg%numerics%erode_dt_ratio), &
              val_t(l=cfg%numerics%sph_viscosity_switch)]
    case (g_gauge)
      associate(g => cfg%gauges(k))
        vals = [val_t(c=g%name), val_t(i=g%node), val_t(i=g%element), val(g%point)]
      end associate
    case default
      associate(o => cfg%output)
        vals = [val_t(c=o%directory), val_t(c=o%case_name, from='the deck file name'), &
                val(o%dt_field), val(o%dt_history), val(o%dt_checkpoint), val_t(i=o%checkpoint_keep)]
      end associate
    end select
    vals%var = vars(group_rows(group_names(gk)))
  end function cfg_vals

  !> The built-in defaults of group kind gk, in table order.
  function default_vals(gk) result(vals)
    integer, intent(in) :: gk
    type(val_t), allocatable :: vals(:)
    type(config_t) :: dflt
    allocate(dflt%materials(1), dflt%parts(1), dflt%boundaries(1), dflt%contacts(1), dflt%gauges(1))
    vals = cfg_vals(dflt, gk, 1)
  end function default_vals

  pure function val_real(x, from) result(v)
    real(rk), intent(in) :: x
    character(len=*), intent(in), optional :: from
    type(val_t) :: v
    allocate(v%r, source=[x])
    if (present(from)) v%from = from
  end function val_real

  pure function val_reals(x) result(v)
    real(rk), intent(in) :: x(:)
    type(val_t) :: v
    allocate(v%r, source=x)
  end function val_reals

  !> A coded choice: the code, its word, and all words as the unit column.
  pure function choice_val(code, words, codes) result(v)
    integer, intent(in) :: code
    character(len=*), intent(in) :: words(:)
    integer, intent(in) :: codes(:)
    type(val_t) :: v
    v%i = code
    v%c = code_word(code, words, codes)
    v%choices = word_list(words, '', '', ' | ')
  end function choice_val

  !> A value as the resolved deck writes it.
  function value_text(x) result(s)
    type(val_t), intent(in) :: x
    character(len=:), allocatable :: s
    select case (x%var%typ)
    case ('r')
      s = r2s_list(x%r)
    case ('i')
      s = itoa(x%i)
    case ('l')
      s = ltoa(x%l)
    case default
      s = qs(x%c)
    end select
  end function value_text

  !> a and b are the same value (coded choices: the same code).
  pure logical function same_value(a, b) result(same)
    type(val_t), intent(in) :: a, b
    select case (a%var%typ)
    case ('r')
      same = all(a%r == b%r)
    case ('i')
      same = a%i == b%i
    case ('l')
      same = a%l .eqv. b%l
    case default
      same = a%i == b%i .and. a%c == b%c
    end select
  end function same_value

  ! ======================================================================
  !  deck_where: message prefixes for other readers (mesh, driver)
  ! ======================================================================

  !> "deck.nml:14: &part #2 'plate'" for the instance-th &group of cfg's deck;
  !> with variable: "deck.nml:15: &part #2 'plate': group = 'plate'" (the line
  !> of that assignment). Rescans the deck file, so it is meant for error paths.
  function deck_where(cfg, group, instance, variable) result(where)
    type(config_t), intent(in) :: cfg
    character(len=*), intent(in) :: group
    integer, intent(in) :: instance
    character(len=*), intent(in), optional :: variable
    character(len=:), allocatable :: where
    type(nml_scan_t) :: scan
    type(inst_t) :: inst
    character(len=256) :: msg
    character(len=:), allocatable :: grp
    integer :: ios, ig, n, k, gk, number

    grp = to_lower(trim(group))
    gk = group_index(grp)
    number = max(instance, 1)
    if (gk > 0) then
      if (group_once(gk)) number = 0       ! once-only groups carry no number
    end if
    call init_inst(inst, grp, number, 0)
    msg = ''
    call nml_scan_file(trim(cfg%deck_file), scan, ios, msg)
    if (ios == 0) then
      n = 0
      do ig = 1, scan%n_groups
        if (scan%groups(ig)%name /= grp) cycle
        n = n + 1
        if (n /= max(instance, 1)) cycle
        inst%line = scan%groups(ig)%start_line
        inst%label = instance_label(scan%groups(ig))
        do k = 1, scan%groups(ig)%n_assign
          call inst_add(inst, scan%groups(ig)%assigns(k)%base, scan%groups(ig)%assigns(k)%value, &
                        scan%groups(ig)%assigns(k)%line)
        end do
        exit
      end do
    end if
    k = 0
    if (present(variable)) k = last_assign(inst, to_lower(trim(variable)))
    if (k > 0) then
      where = nml_location(scan, inst%a(k)%line, trim(cfg%deck_file))//': '//prefix(inst)// &
              trim(variable)//' = '//as_single_quoted(inst%a(k)%value)
    else
      where = trim(cfg%deck_file)
      if (inst%line > 0) where = nml_location(scan, inst%line, trim(cfg%deck_file))
      where = where//': '//prefix(inst)
      where = where(1:len(where)-2)          ! prefix() ends with ': '
      if (present(variable)) where = where//': '//trim(variable)
    end if
  end function deck_where

  ! ======================================================================
  !  instance records and messages
  ! ======================================================================

  subroutine init_inst(inst, grp, number, line)
    type(inst_t), intent(inout) :: inst
    character(len=*), intent(in) :: grp
    integer, intent(in) :: number, line
    inst%grp = grp
    inst%number = number
    inst%line = line
    inst%label = ''
    if (allocated(inst%a)) deallocate(inst%a)
    allocate(inst%a(0))
  end subroutine init_inst

  ! Records and messages grow by one at a time: a deck has tens of them.

  subroutine inst_add(inst, base, value, line, bad)
    type(inst_t), intent(inout) :: inst
    character(len=*), intent(in) :: base, value
    integer, intent(in) :: line
    logical, intent(in), optional :: bad
    inst%a = [inst%a, asg_t(base=base, value=value, line=line)]
    if (present(bad)) inst%a(size(inst%a))%bad = bad
  end subroutine inst_add

  !> Index of the last assignment to name (base name, any subscript), 0 if none.
  pure integer function last_assign(inst, name) result(k)
    type(inst_t), intent(in) :: inst
    character(len=*), intent(in) :: name
    do k = size(inst%a), 1, -1
      if (inst%a(k)%base == name) return
    end do
    k = 0
  end function last_assign

  pure logical function is_set(inst, name)
    type(inst_t), intent(in) :: inst
    character(len=*), intent(in) :: name
    is_set = last_assign(inst, name) > 0
  end function is_set

  !> Some assignment to name could not be read (and was reported).
  pure logical function is_bad(inst, name)
    type(inst_t), intent(in) :: inst
    character(len=*), intent(in) :: name
    is_bad = any(inst%a%base == name .and. inst%a%bad)
  end function is_bad

  !> "&material #1 (line 4)": an earlier instance, in messages about a later one.
  function instance_ref(inst) result(s)
    type(inst_t), intent(in) :: inst
    character(len=:), allocatable :: s
    s = '&'//trim(inst%grp)//' #'//itoa(inst%number)//' (line '//itoa(inst%line)//')'
  end function instance_ref

  !> "&material #1 'copper': " or "&run: ".
  function prefix(inst) result(p)
    type(inst_t), intent(in) :: inst
    character(len=:), allocatable :: p
    p = '&'//trim(inst%grp)
    if (inst%number > 0) p = p//' #'//itoa(inst%number)
    if (allocated(inst%label)) then
      if (len(inst%label) > 0) p = p//" '"//inst%label//"'"
    end if
    p = p//': '
  end function prefix

  !> What names a group instance in messages: the material name, the part's
  !> mesh group, the boundary's surface or kind, the contact's master or
  !> slave (as written in the deck).
  function instance_label(gr) result(label)
    type(nml_group_t), intent(in) :: gr
    character(len=:), allocatable :: label
    character(len=16) :: keys(2)
    integer :: k, j
    select case (gr%name)
    case ('material')
      keys = [character(len=16) :: 'name', '']
    case ('part')
      keys = [character(len=16) :: 'group', '']
    case ('boundary')
      keys = [character(len=16) :: 'surface', 'kind']
    case ('contact')
      keys = [character(len=16) :: 'master', 'slave']
    case ('gauge')
      keys = [character(len=16) :: 'name', '']
    case default
      keys = ''
    end select
    label = ''
    do j = 1, 2
      if (len_trim(keys(j)) == 0) cycle
      do k = gr%n_assign, 1, -1
        if (gr%assigns(k)%base == trim(keys(j)) .and. gr%assigns(k)%ok) then
          label = shorten(quoted_text(gr%assigns(k)%value, whole=.false.), 40)
          if (len(label) > 0) return
        end if
      end do
    end do
  end function instance_label

  subroutine report(ctx, line, text)
    type(ctx_t), intent(inout) :: ctx
    integer, intent(in) :: line
    character(len=*), intent(in) :: text
    ! a file that is no deck could give thousands: the first ones tell enough
    if (size(ctx%d) >= max_messages) then
      ctx%n_dropped = ctx%n_dropped + 1
      return
    end if
    if (line > 0) then
      ctx%d = [ctx%d, diag_t(line, nml_location(ctx%lines, line, ctx%path)//': '//text)]
    else
      ctx%d = [ctx%d, diag_t(line, ctx%path//': '//text)]
    end if
  end subroutine report

  !> Stable insertion sort by line (deck-wide messages, line 0, first).
  subroutine sort_diags(ctx)
    type(ctx_t), intent(inout) :: ctx
    type(diag_t) :: t
    integer :: i, j
    do i = 2, size(ctx%d)
      t = ctx%d(i)
      j = i - 1
      do while (j >= 1)
        if (ctx%d(j)%line <= t%line) exit
        ctx%d(j+1) = ctx%d(j)
        j = j - 1
      end do
      ctx%d(j+1) = t
    end do
  end subroutine sort_diags

  ! ======================================================================
  !  names, suggestions, explanations
  ! ======================================================================

  pure integer function group_index(name) result(gk)
    character(len=*), intent(in) :: name
    do gk = 1, n_group_kinds
      if (trim(group_names(gk)) == name) return
    end do
    gk = 0
  end function group_index

  !> Table rows of the variables of group grp, in table order.
  pure function group_rows(grp) result(rows)
    character(len=*), intent(in) :: grp
    integer, allocatable :: rows(:)
    integer :: iv
    rows = pack([(iv, iv = 1, size(vars))], vars%grp == grp)
  end function group_rows

  pure integer function var_index(grp, name) result(iv)
    character(len=*), intent(in) :: grp, name
    do iv = 1, size(vars)
      if (trim(vars(iv)%grp) == grp .and. trim(vars(iv)%name) == name) return
    end do
    iv = 0
  end function var_index

  function group_suggestion(name) result(s)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: s
    s = suggestion(name, group_names, '&', '')
    if (len(s) == 0) s = ' (groups: '//word_list(group_names, '&', '', ', ')//')'
  end function group_suggestion

  !> "unknown variable 'x' in &grp (did you mean 'y'?)", or where x belongs,
  !> or the list of valid names.
  function unknown_var_text(grp, name, suggested) result(s)
    character(len=*), intent(in) :: grp, name
    character(len=:), allocatable, intent(out) :: suggested   !< the likely intended name, or ''
    character(len=:), allocatable :: s
    character(len=20), allocatable :: names(:)
    character(len=:), allocatable :: others
    integer :: iv, j

    names = vars(group_rows(grp))%name
    s = "unknown variable '"//name//"' in &"//grp
    suggested = ''
    j = closest_word(name, names)
    if (j > 0) then
      suggested = trim(names(j))
      s = s//" (did you mean '"//suggested//"'?)"
      return
    end if
    others = ''
    do iv = 1, size(vars)
      if (trim(vars(iv)%name) == name .and. trim(vars(iv)%grp) /= grp) &
           others = others//' &'//trim(vars(iv)%grp)
    end do
    if (len(others) > 0) then
      s = s//" ('"//name//"' belongs in"//others//')'
    else
      s = s//' (valid: '//quoted_list(names)//')'
    end if
  end function unknown_var_text

  !> " (did you mean 'y'?)" for the closest word, '' if none is close.
  function suggestion(name, words, lq, rq) result(s)
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: words(:)
    character(len=*), intent(in) :: lq, rq     !< quotes put around the suggested word
    character(len=:), allocatable :: s
    integer :: j
    j = closest_word(name, words)
    s = ''
    if (j > 0) s = ' (did you mean '//lq//trim(words(j))//rq//'?)'
  end function suggestion

  !> Index of the word closest to name by edit distance (or a word that starts
  !> with name), 0 if none is close enough to be a likely typo.
  integer function closest_word(name, words) result(jbest)
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: words(:)
    integer :: j, d, best, limit
    best = huge(1)
    jbest = 0
    do j = 1, size(words)
      d = edit_distance(name, trim(words(j)))
      if (d < best) then
        best = d
        jbest = j
      end if
    end do
    limit = max(1, min(3, len(name) / 3))
    if (jbest > 0 .and. best <= limit) return
    jbest = 0
    if (len(name) >= 3) then
      do j = 1, size(words)
        if (index(trim(words(j)), name) == 1) then
          jbest = j
          return
        end if
      end do
    end if
  end function closest_word

  !> Optimal string alignment distance (Levenshtein plus adjacent swaps).
  pure integer function edit_distance(a, b) result(dist)
    character(len=*), intent(in) :: a, b
    integer :: d(0:len(a), 0:len(b)), i, j, cost
    do i = 0, len(a)
      d(i, 0) = i
    end do
    do j = 0, len(b)
      d(0, j) = j
    end do
    do i = 1, len(a)
      do j = 1, len(b)
        cost = merge(0, 1, a(i:i) == b(j:j))
        d(i, j) = min(d(i-1, j) + 1, d(i, j-1) + 1, d(i-1, j-1) + cost)
        if (i > 1 .and. j > 1) then
          if (a(i:i) == b(j-1:j-1) .and. a(i-1:i-1) == b(j:j)) d(i, j) = min(d(i, j), d(i-2, j-2) + 1)
        end if
      end do
    end do
    dist = d(len(a), len(b))
  end function edit_distance

  !> Why "name = value" alone does not read, in words an analyst can act on.
  function read_failure_text(grp, name, base, value, iomsg) result(s)
    character(len=*), intent(in) :: grp, name, base, value, iomsg
    character(len=:), allocatable :: s
    integer :: iv
    character(len=:), allocatable :: word

    iv = var_index(grp, base)
    if (name /= base) then
      ! subscripted
      if (vars(iv)%n == 1) then
        s = "'"//base//"' is not an array: write "//base//' = value'
        return
      else if (index(iomsg, 'range') > 0) then
        s = 'subscript out of range: '//base//' has '//itoa(vars(iv)%n)//' components'
        return
      end if
    end if
    select case (vars(iv)%typ)
    case ('r')
      if (vars(iv)%n == 1) then
        s = 'not a valid real number'
      else
        s = 'not a valid list of at most '//itoa(vars(iv)%n)//' real numbers'
      end if
    case ('i')
      if (index(iomsg, 'verflow') > 0) then
        s = 'integer too large (at most '//itoa(huge(1))//')'
      else
        s = 'not a valid integer'
      end if
    case ('l')
      s = 'not a valid logical: use .true. or .false.'
    case default
      if (value(1:1) /= "'" .and. value(1:1) /= '"') then
        s = "not a valid string: text must be in quotes, e.g. "//base//" = '"// &
            value(1:max(1, scan(value//' ', ' ,') - 1))//"'"
      else
        s = 'not a valid string: one quoted text expected'
      end if
    end select
    ! "a = 1 b 2": a missing '=' makes the next name part of this value
    word = known_word_in(grp, value)
    if (len(word) > 0) s = s//" (missing '=' after '"//word//"'?)"
  end function read_failure_text

  !> The first blank- or comma-separated word of value (outside quotes) that
  !> is a variable of grp, or ''.
  function known_word_in(grp, value) result(word)
    character(len=*), intent(in) :: grp, value
    character(len=:), allocatable :: word
    integer :: i, j
    character :: q
    i = 1
    q = ' '
    word = ''
    do while (i <= len(value))
      if (q /= ' ') then
        if (value(i:i) == q) q = ' '
        i = i + 1
        cycle
      end if
      if (value(i:i) == "'" .or. value(i:i) == '"') then
        q = value(i:i)
        i = i + 1
        cycle
      end if
      if (value(i:i) == ' ' .or. value(i:i) == ',') then
        i = i + 1
        cycle
      end if
      j = i
      do while (j <= len(value))
        if (index(" ,'"//'"', value(j:j)) > 0) exit
        j = j + 1
      end do
      if (var_index(grp, to_lower(value(i:j-1))) > 0) then
        word = to_lower(value(i:j-1))
        return
      end if
      i = j
    end do
  end function known_word_in


  !> The words joined by sep, each between open and close.
  pure function word_list(words, open, close, sep) result(s)
    character(len=*), intent(in) :: words(:)
    character(len=*), intent(in) :: open, close, sep
    character(len=:), allocatable :: s
    integer :: j
    s = ''
    do j = 1, size(words)
      if (j > 1) s = s//sep
      s = s//open//trim(words(j))//close
    end do
  end function word_list

  !> "'a', 'b', 'c'".
  pure function quoted_list(words) result(s)
    character(len=*), intent(in) :: words(:)
    character(len=:), allocatable :: s
    s = word_list(words, "'", "'", ', ')
  end function quoted_list

  !> word is one of the blank-separated words of list.
  pure logical function in_list(word, list)
    character(len=*), intent(in) :: word, list
    in_list = index(' '//list//' ', ' '//word//' ') > 0
  end function in_list

  pure function code_word(code, words, codes) result(w)
    integer, intent(in) :: code
    character(len=*), intent(in) :: words(:)
    integer, intent(in) :: codes(:)
    character(len=:), allocatable :: w
    integer :: j
    w = ''
    do j = 1, size(codes)
      if (codes(j) == code) w = trim(words(j))
    end do
  end function code_word

  ! ======================================================================
  !  small text helpers
  ! ======================================================================


  !> The text of the quoted string that v starts with, a doubled quote read as
  !> one quote; '' if v does not start with a quote. whole: v is one string
  !> value (namelist reading): it must end with the opening quote too, and any
  !> quote inside counts as doubled. Otherwise the string ends at its first
  !> lone quote: this names a group instance even when the value is broken.
  pure function quoted_text(v, whole) result(s)
    character(len=*), intent(in) :: v
    logical, intent(in) :: whole
    character(len=:), allocatable :: s
    character :: q
    character(len=:), allocatable :: buf
    integer :: i, k, last
    s = ''
    if (len(v) < 2) return
    q = v(1:1)
    if (q /= "'" .and. q /= '"') return
    last = len(v)
    if (whole) then
      if (v(last:last) /= q) return
      last = last - 1
    end if
    ! built in a buffer: appending one character at a time is quadratic,
    ! 80 s for a 1 MB string
    allocate(character(len=last) :: buf)
    k = 0
    i = 2
    do while (i <= last)
      if (v(i:i) == q .and. .not. whole) then
        if (i == len(v)) exit
        if (v(i+1:i+1) /= q) exit
      end if
      k = k + 1
      buf(k:k) = v(i:i)
      if (v(i:i) == q) i = i + 1     ! doubled quote
      i = i + 1
    end do
    s = buf(1:k)
  end function quoted_text

  !> A value that is one string, written with single quotes ("rod" -> 'rod');
  !> any other value unchanged.
  pure function as_single_quoted(v) result(s)
    character(len=*), intent(in) :: v
    character(len=:), allocatable :: s
    s = v
    if (len(v) < 2) return
    if ((v(1:1) == '"' .or. v(1:1) == "'") .and. v(len(v):len(v)) == v(1:1)) then
      if (qs(quoted_text(v, whole=.true.)) /= qs(quoted_text(v, whole=.false.))) return   ! several strings
      s = qs(quoted_text(v, whole=.true.))
    end if
  end function as_single_quoted

  !> Four significant digits, for a value quoted beside another: '1.667e11'.
  function sig4(x) result(s)
    real(rk), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    integer :: k, e
    write(buf, '(es12.3e3)') x
    s = trim(adjustl(buf))
    k = index(s, 'E')
    if (k == 0) return
    read(s(k+1:), *) e
    s = s(1:k-1)//'e'//itoa(e)
  end function sig4

  !> A relative difference in per cent, one decimal, with its sign: '-49.2 %'.
  function pct(x) result(s)
    real(rk), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    write(buf, '(sp,f0.1,a)') 100 * x, ' %'
    s = trim(buf)
  end function pct

  !> Whether a value reads as one logical: [r*][.]T or [r*][.]F (any case,
  !> anything after the letter), as list-directed input accepts it.
  pure logical function logical_text(v) result(ok)
    character(len=*), intent(in) :: v
    integer :: i
    ok = .false.
    i = verify(v, '0123456789')           ! a repeat count "3*" is skipped
    if (i == 0) return
    if (i > 1 .and. v(i:i) == '*') then
      i = i + 1
    else
      i = 1
    end if
    if (i > len(v)) return
    if (v(i:i) == '.') i = i + 1
    if (i > len(v)) return
    ok = index('tTfF', v(i:i)) > 0
  end function logical_text

  !> Characters in a quoted value; 0 if it is not a quoted string.
  pure integer function quoted_length(v)
    character(len=*), intent(in) :: v
    quoted_length = len(quoted_text(v, whole=.true.))
  end function quoted_length

  !> A string as a namelist value: quoted, inner quotes doubled, trimmed.
  pure function qs(v) result(s)
    character(len=*), intent(in) :: v
    character(len=:), allocatable :: s
    s = "'"//replace(trim(v), "'", "''")//"'"
  end function qs


  function r2s_list(x) result(s)
    real(rk), intent(in) :: x(:)
    character(len=:), allocatable :: s
    integer :: i
    s = ''
    do i = 1, size(x)
      if (i > 1) s = s//', '
      s = s//r2s(x(i))
    end do
  end function r2s_list

  pure function ltoa(l) result(s)
    logical, intent(in) :: l
    character(len=:), allocatable :: s
    if (l) then
      s = '.true.'
    else
      s = '.false.'
    end if
  end function ltoa

  !> File name without folder and extension: 'decks/impact.nml' -> 'impact'.
  pure function stem_of(path) result(s)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: s
    integer :: k
    s = base_name(path)
    k = index(s, '.', back=.true.)
    if (k > 1) s = s(1:k-1)
  end function stem_of


  !> Absolute, canonical path of an existing file; the input if that fails.
  function absolute_path(path) result(abs_path)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: abs_path
    character(kind=c_char) :: buf(4097)
    type(c_ptr) :: p
    integer :: i
    abs_path = path
    buf = c_null_char
    p = c_realpath(path//c_null_char, buf)
    if (.not. c_associated(p)) return
    abs_path = ''
    do i = 1, size(buf)
      if (buf(i) == c_null_char) exit
      abs_path = abs_path//buf(i)
    end do
    if (len(abs_path) > max_path_len) abs_path = path
  end function absolute_path

end module udar_deck
