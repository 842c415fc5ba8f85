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
module udar_deck
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use, intrinsic :: ieee_exceptions, only: ieee_status_type, ieee_get_status, ieee_set_status, &
       ieee_set_halting_mode, ieee_usual
  use, intrinsic :: iso_c_binding, only: c_char, c_ptr, c_null_char, c_associated
  use udar_kinds, only: rk, max_name_len, max_path_len
  use udar_config, only: config_t, run_cfg_t, mesh_cfg_t, material_cfg_t, part_cfg_t, &
       boundary_cfg_t, numerics_cfg_t, output_cfg_t, eos_linear, eos_mie_gruneisen, &
       strength_none, strength_elastic, strength_perfectly_plastic, strength_linear_hardening, &
       strength_johnson_cook, bc_fixed, bc_symmetry, bc_rigid_wall, wall_frictionless, wall_sticking
  use udar_input_errors, only: input_errors_t
  use udar_nml_scan, only: nml_scan_t, nml_group_t, nml_scan_file, nml_lower
  implicit none
  private
  public :: deck_read, deck_write_resolved, deck_where

  character(len=*), parameter :: nl = achar(10)
  integer, parameter :: code_len = 32          !< length of the deck strings for coded choices
  real(rk), parameter :: rel_tol = 1.0e-6_rk   !< agreement asked of redundant elastic constants

  ! defaults, taken from udar_config so that they live in one place
  type(run_cfg_t), parameter :: run_dflt = run_cfg_t()
  type(mesh_cfg_t), parameter :: mesh_dflt = mesh_cfg_t()
  type(material_cfg_t), parameter :: mat_dflt = material_cfg_t()
  type(part_cfg_t), parameter :: part_dflt = part_cfg_t()
  type(boundary_cfg_t), parameter :: bnd_dflt = boundary_cfg_t()
  type(numerics_cfg_t), parameter :: num_dflt = numerics_cfg_t()
  type(output_cfg_t), parameter :: out_dflt = output_cfg_t()
  integer, parameter :: title_len = len(run_dflt%title)

  ! ------------------------------------------------------------ the groups
  integer, parameter :: n_group_kinds = 7
  integer, parameter :: g_run = 1, g_mesh = 2, g_material = 3, g_part = 4, g_boundary = 5, &
                        g_numerics = 6, g_output = 7    !< indices into the tables below
  character(len=8), parameter :: group_names(n_group_kinds) = [character(len=8) :: &
       'run', 'mesh', 'material', 'part', 'boundary', 'numerics', 'output']
  logical, parameter :: group_once(n_group_kinds) = &
       [.true., .true., .false., .false., .false., .true., .true.]
  logical, parameter :: group_required(n_group_kinds) = &
       [.true., .true., .true., .true., .false., .false., .false.]
  character(len=40), parameter :: group_purpose(n_group_kinds) = [character(len=40) :: &
       'end time and time step control', 'the mesh file', 'material models', &
       'bodies: mesh volume, material, velocity', 'boundary conditions', 'solver options', &
       'output files']

  ! ------------------------------------------------- string forms of the codes
  character(len=20), parameter :: eos_words(2) = [character(len=20) :: 'linear', 'mie_gruneisen']
  integer, parameter :: eos_codes(2) = [eos_linear, eos_mie_gruneisen]
  character(len=20), parameter :: strength_words(5) = [character(len=20) :: 'none', 'elastic', &
       'perfectly_plastic', 'linear_hardening', 'johnson_cook']
  integer, parameter :: strength_codes(5) = [strength_none, strength_elastic, &
       strength_perfectly_plastic, strength_linear_hardening, strength_johnson_cook]
  character(len=20), parameter :: kind_words(3) = [character(len=20) :: 'fixed', 'symmetry', 'rigid_wall']
  integer, parameter :: kind_codes(3) = [bc_fixed, bc_symmetry, bc_rigid_wall]
  character(len=20), parameter :: wall_words(2) = [character(len=20) :: 'frictionless', 'sticking']
  integer, parameter :: wall_codes(2) = [wall_frictionless, wall_sticking]

  ! ------------------------------------------------------ the variable table
  !> One deck variable: used for unknown-name suggestions and read-failure
  !> explanations. (Units and defaults are written out in write_resolved.)
  type :: var_t
    character(len=8) :: grp
    character(len=20) :: name
    character :: typ        !< r real, i integer, l logical, c character
    integer :: n            !< number of components
    integer :: clen         !< longest accepted string (typ c)
  end type

  type(var_t), parameter :: vars(*) = [ &
       var_t('run', 'title', 'c', 1, title_len), &
       var_t('run', 't_end', 'r', 1, 0), &
       var_t('run', 'dt_safety', 'r', 1, 0), &
       var_t('run', 'dt_initial', 'r', 1, 0), &
       var_t('run', 'dt_max', 'r', 1, 0), &
       var_t('run', 'max_cycles', 'i', 1, 0), &
       var_t('run', 'cycle_print', 'i', 1, 0), &
       var_t('run', 'energy_error_limit', 'r', 1, 0), &
       var_t('run', 'wall_limit', 'r', 1, 0), &
       var_t('mesh', 'file', 'c', 1, max_path_len), &
       var_t('mesh', 'scale', 'r', 1, 0), &
       var_t('material', 'name', 'c', 1, max_name_len), &
       var_t('material', 'rho0', 'r', 1, 0), &
       var_t('material', 'eos', 'c', 1, code_len), &
       var_t('material', 'bulk_modulus', 'r', 1, 0), &
       var_t('material', 'c0', 'r', 1, 0), &
       var_t('material', 's', 'r', 1, 0), &
       var_t('material', 'gamma0', 'r', 1, 0), &
       var_t('material', 'strength', 'c', 1, code_len), &
       var_t('material', 'shear_modulus', 'r', 1, 0), &
       var_t('material', 'youngs_modulus', 'r', 1, 0), &
       var_t('material', 'poisson_ratio', 'r', 1, 0), &
       var_t('material', 'yield_stress', 'r', 1, 0), &
       var_t('material', 'hardening_modulus', 'r', 1, 0), &
       var_t('material', 'jc_a', 'r', 1, 0), &
       var_t('material', 'jc_b', 'r', 1, 0), &
       var_t('material', 'jc_n', 'r', 1, 0), &
       var_t('material', 'jc_c', 'r', 1, 0), &
       var_t('material', 'jc_m', 'r', 1, 0), &
       var_t('material', 'jc_rate0', 'r', 1, 0), &
       var_t('material', 't_melt', 'r', 1, 0), &
       var_t('material', 't_room', 'r', 1, 0), &
       var_t('material', 'specific_heat', 'r', 1, 0), &
       var_t('material', 'taylor_quinney', 'r', 1, 0), &
       var_t('material', 'initial_temperature', 'r', 1, 0), &
       var_t('part', 'group', 'c', 1, max_name_len), &
       var_t('part', 'material', 'c', 1, max_name_len), &
       var_t('part', 'velocity', 'r', 3, 0), &
       var_t('boundary', 'kind', 'c', 1, code_len), &
       var_t('boundary', 'surface', 'c', 1, max_name_len), &
       var_t('boundary', 'point', 'r', 3, 0), &
       var_t('boundary', 'normal', 'r', 3, 0), &
       var_t('boundary', 'wall_type', 'c', 1, code_len), &
       var_t('numerics', 'anti_locking', 'l', 1, 0), &
       var_t('numerics', 'q_linear', 'r', 1, 0), &
       var_t('numerics', 'q_quadratic', 'r', 1, 0), &
       var_t('output', 'directory', 'c', 1, max_path_len), &
       var_t('output', 'case_name', 'c', 1, max_name_len), &
       var_t('output', 'dt_field', 'r', 1, 0), &
       var_t('output', 'dt_history', 'r', 1, 0) ]

  ! ----------------------------------------------------- working data types
  !> The namelist variables of one group instance while it is read. The coded
  !> choices stay strings here; they become codes after the read.
  type :: values_t
    type(run_cfg_t) :: run
    type(mesh_cfg_t) :: mesh
    type(material_cfg_t) :: mat
    type(part_cfg_t) :: part
    type(boundary_cfg_t) :: bnd
    type(numerics_cfg_t) :: num
    type(output_cfg_t) :: out
    character(len=code_len) :: eos = 'linear'
    character(len=code_len) :: strength = 'elastic'
    character(len=code_len) :: kind = ''
    character(len=code_len) :: wall_type = 'frictionless'
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
    integer :: na = 0
    type(asg_t), allocatable :: a(:)
  end type

  !> Assignment records of a whole deck.
  type :: track_t
    type(inst_t) :: run, mesh, numerics, output
    type(inst_t), allocatable :: materials(:), parts(:), boundaries(:)
  end type

  type :: diag_t
    integer :: line = 0
    character(len=:), allocatable :: text
  end type

  !> Messages of one deck_read, sorted by line before they are handed out.
  type :: ctx_t
    character(len=:), allocatable :: path
    integer :: n = 0
    type(diag_t), allocatable :: d(:)
  end type

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
    character(len=code_len), allocatable :: eos_txt(:), str_txt(:), kind_txt(:), wall_txt(:)
    integer :: ios, k, j, ig, gk, first(n_group_kinds), cnt(n_group_kinds), nmat, npart, nbnd
    logical :: misspelled(n_group_kinds)

    cfg%deck_file = path
    ctx%path = trim(path)
    allocate(ctx%d(16))

    msg = ''
    call nml_scan_file(trim(path), scan, ios, msg)
    if (ios /= 0) then
      call errors%add(trim(path)//': cannot read the deck file: '//trim(msg))
      return
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

    nmat = cnt(g_material)
    npart = cnt(g_part)
    nbnd = cnt(g_boundary)
    allocate(cfg%materials(nmat), cfg%parts(npart), cfg%boundaries(nbnd))
    allocate(tr%materials(nmat), tr%parts(npart), tr%boundaries(nbnd))
    allocate(eos_txt(nmat), str_txt(nmat), kind_txt(nbnd), wall_txt(nbnd))
    call init_inst(tr%run, 'run', 0, 0)
    call init_inst(tr%mesh, 'mesh', 0, 0)
    call init_inst(tr%numerics, 'numerics', 0, 0)
    call init_inst(tr%output, 'output', 0, 0)

    ! read every group instance
    nmat = 0
    npart = 0
    nbnd = 0
    do ig = 1, scan%n_groups
      gk = group_index(scan%groups(ig)%name)
      if (gk == 0) cycle
      if (group_once(gk) .and. first(gk) /= ig) cycle
      v = values_t()
      select case (gk)
      case (g_run)
        call read_instance(ctx, scan%groups(ig), tr%run, 0, v)
        cfg%run = v%run
      case (g_mesh)
        call read_instance(ctx, scan%groups(ig), tr%mesh, 0, v)
        cfg%mesh = v%mesh
      case (g_material)
        nmat = nmat + 1
        call read_instance(ctx, scan%groups(ig), tr%materials(nmat), nmat, v)
        cfg%materials(nmat) = v%mat
        eos_txt(nmat) = v%eos
        str_txt(nmat) = v%strength
      case (g_part)
        npart = npart + 1
        call read_instance(ctx, scan%groups(ig), tr%parts(npart), npart, v)
        cfg%parts(npart) = v%part
      case (g_boundary)
        nbnd = nbnd + 1
        call read_instance(ctx, scan%groups(ig), tr%boundaries(nbnd), nbnd, v)
        cfg%boundaries(nbnd) = v%bnd
        kind_txt(nbnd) = v%kind
        wall_txt(nbnd) = v%wall_type
      case (g_numerics)
        call read_instance(ctx, scan%groups(ig), tr%numerics, 0, v)
        cfg%numerics = v%num
      case (g_output)
        call read_instance(ctx, scan%groups(ig), tr%output, 0, v)
        cfg%output = v%out
      end select
    end do

    ! check values, fill in derived ones
    if (tr%run%line > 0) call check_run(ctx, tr%run, cfg%run)
    if (tr%mesh%line > 0) call check_mesh(ctx, tr%mesh, cfg%mesh, trim(path))
    do k = 1, nmat
      call check_material(ctx, tr%materials(k), cfg%materials(k), eos_txt(k), str_txt(k), &
                          cfg%materials(1:k-1), tr%materials(1:k-1))
    end do
    do k = 1, npart
      call check_part(ctx, tr%parts(k), cfg%parts(k), cfg%parts(1:k-1), tr%parts(1:k-1), &
                      cfg%materials, nmat)
    end do
    do k = 1, nbnd
      call check_boundary(ctx, tr%boundaries(k), cfg%boundaries(k), kind_txt(k), wall_txt(k))
    end do
    call check_numerics(ctx, tr%numerics, cfg%numerics)
    call check_output(ctx, tr%output, cfg%output, trim(path))

    ! hand the messages out in line order
    call sort_diags(ctx)
    do k = 1, ctx%n
      call errors%add(ctx%d(k)%text)
    end do

    if (ctx%n == 0) then
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
        slot(k) = inst%na
        if (.not. a%ok) then
          ! the scan has already reported this assignment
          inst%a(inst%na)%bad = .true.
          diagnose = .true.
          cycle
        end if
        iv = var_index(grp, a%base)
        if (iv == 0) then
          call report(ctx, a%line, prefix(inst)//unknown_var_text(grp, a%base, meant))
          inst%a(inst%na)%bad = .true.
          diagnose = .true.
          ! the misspelled variable counts as given but unreadable, so that the
          ! checks do not also call it missing
          if (len(meant) > 0) then
            call inst_add(inst, meant, a%value, a%line)
            inst%a(inst%na)%bad = .true.
          end if
          cycle
        end if
        if (len(a%value) == 0) then
          call report(ctx, a%line, prefix(inst)//a%name//' = : no value given')
          inst%a(inst%na)%bad = .true.
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
            inst%a(inst%na)%bad = .true.
            diagnose = .true.
          end if
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
        call check_finite(ctx, inst, v)
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
          if (len(meant) > 0) then
            call inst_add(inst, meant, a%value, a%line)
            inst%a(inst%na)%bad = .true.
          end if
        end if
      end associate
    end do
    if (nfail == 0 .and. .not. diagnose) then
      ! every assignment reads alone, the group as a whole does not
      call report(ctx, gr%start_line, prefix(inst)//'the group cannot be read as a namelist: '// &
           trim(whole_msg))
      do k = 1, inst%na
        inst%a(k)%bad = .true.
      end do
    end if
    call check_finite(ctx, inst, v)
  end subroutine read_instance

  !> Every real the deck set must be a finite number (namelist input accepts
  !> NaN, Inf and 1e400). Reported once here; later checks skip them.
  subroutine check_finite(ctx, inst, v)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(inout) :: inst
    type(values_t), intent(in) :: v
    character(len=20), allocatable :: names(:)
    logical, allocatable :: finite(:)
    integer :: j, k

    call real_finiteness(inst%grp, v, names, finite)
    do j = 1, size(names)
      if (finite(j) .or. is_bad(inst, trim(names(j)))) cycle
      k = last_assign(inst, trim(names(j)))
      if (k == 0) cycle
      call report(ctx, inst%a(k)%line, prefix(inst)//trim(names(j))//' = '// &
           shorten(inst%a(k)%value)//' : not a finite number')
      inst%a(k)%bad = .true.
    end do
  end subroutine check_finite

  !> Names of the real variables of group grp and whether their values are finite.
  subroutine real_finiteness(grp, v, names, finite)
    character(len=*), intent(in) :: grp
    type(values_t), intent(in) :: v
    character(len=20), allocatable, intent(out) :: names(:)
    logical, allocatable, intent(out) :: finite(:)
    call group_var_names(grp, 'r', names)
    allocate(finite(size(names)))
    finite = .true.
    select case (grp)
    case ('run')
      finite = ieee_is_finite([v%run%t_end, v%run%dt_safety, v%run%dt_initial, v%run%dt_max, &
                               v%run%energy_error_limit, v%run%wall_limit])
    case ('mesh')
      finite = ieee_is_finite([v%mesh%scale])
    case ('material')
      associate(m => v%mat)
        finite = ieee_is_finite([m%rho0, m%bulk_modulus, m%c0, m%s, m%gamma0, m%shear_modulus, &
             m%youngs_modulus, m%poisson_ratio, m%yield_stress, m%hardening_modulus, m%jc_a, &
             m%jc_b, m%jc_n, m%jc_c, m%jc_m, m%jc_rate0, m%t_melt, m%t_room, m%specific_heat, &
             m%taylor_quinney, m%initial_temperature])
      end associate
    case ('part')
      finite = [all(ieee_is_finite(v%part%velocity))]
    case ('boundary')
      finite = [all(ieee_is_finite(v%bnd%point)), all(ieee_is_finite(v%bnd%normal))]
    case ('numerics')
      finite = ieee_is_finite([v%num%q_linear, v%num%q_quadratic])
    case ('output')
      finite = ieee_is_finite([v%out%dt_field, v%out%dt_history])
    end select
  end subroutine real_finiteness

  !> Namelist READ of text (one whole group, '&grp ... /') into v.
  subroutine read_nml(grp, text, v, ios, msg)
    character(len=*), intent(in) :: grp, text
    type(values_t), intent(inout) :: v
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    select case (grp)
    case ('run')
      call nml_run(text, v, ios, msg)
    case ('mesh')
      call nml_mesh(text, v, ios, msg)
    case ('material')
      call nml_material(text, v, ios, msg)
    case ('part')
      call nml_part(text, v, ios, msg)
    case ('boundary')
      call nml_boundary(text, v, ios, msg)
    case ('numerics')
      call nml_numerics(text, v, ios, msg)
    case ('output')
      call nml_output(text, v, ios, msg)
    case default
      ios = -1
    end select
  end subroutine read_nml

  ! One reader per group: the namelist variables are locals named as in the
  ! deck, loaded from v before the READ and stored back only if it succeeded
  ! (a failed READ may have changed some of them).

  subroutine nml_run(text, v, ios, msg)
    character(len=*), intent(in) :: text
    type(values_t), intent(inout) :: v
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    character(len=title_len) :: title
    real(rk) :: t_end, dt_safety, dt_initial, dt_max, energy_error_limit, wall_limit
    integer :: max_cycles, cycle_print
    namelist /run/ title, t_end, dt_safety, dt_initial, dt_max, max_cycles, cycle_print, &
                   energy_error_limit, wall_limit
    title = v%run%title
    t_end = v%run%t_end
    dt_safety = v%run%dt_safety
    dt_initial = v%run%dt_initial
    dt_max = v%run%dt_max
    max_cycles = v%run%max_cycles
    cycle_print = v%run%cycle_print
    energy_error_limit = v%run%energy_error_limit
    wall_limit = v%run%wall_limit
    read(text, nml=run, iostat=ios, iomsg=msg)
    if (ios /= 0) return
    v%run%title = title
    v%run%t_end = t_end
    v%run%dt_safety = dt_safety
    v%run%dt_initial = dt_initial
    v%run%dt_max = dt_max
    v%run%max_cycles = max_cycles
    v%run%cycle_print = cycle_print
    v%run%energy_error_limit = energy_error_limit
    v%run%wall_limit = wall_limit
  end subroutine nml_run

  subroutine nml_mesh(text, v, ios, msg)
    character(len=*), intent(in) :: text
    type(values_t), intent(inout) :: v
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    character(len=max_path_len) :: file
    real(rk) :: scale
    namelist /mesh/ file, scale
    file = v%mesh%file
    scale = v%mesh%scale
    read(text, nml=mesh, iostat=ios, iomsg=msg)
    if (ios /= 0) return
    v%mesh%file = file
    v%mesh%scale = scale
  end subroutine nml_mesh

  subroutine nml_material(text, v, ios, msg)
    character(len=*), intent(in) :: text
    type(values_t), intent(inout) :: v
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    character(len=max_name_len) :: name
    character(len=code_len) :: eos, strength
    real(rk) :: rho0, bulk_modulus, c0, s, gamma0, shear_modulus, youngs_modulus, poisson_ratio, &
                yield_stress, hardening_modulus, jc_a, jc_b, jc_n, jc_c, jc_m, jc_rate0, t_melt, &
                t_room, specific_heat, taylor_quinney, initial_temperature
    namelist /material/ name, rho0, eos, bulk_modulus, c0, s, gamma0, strength, shear_modulus, &
                        youngs_modulus, poisson_ratio, yield_stress, hardening_modulus, jc_a, &
                        jc_b, jc_n, jc_c, jc_m, jc_rate0, t_melt, t_room, specific_heat, &
                        taylor_quinney, initial_temperature
    name = v%mat%name
    eos = v%eos
    strength = v%strength
    rho0 = v%mat%rho0
    bulk_modulus = v%mat%bulk_modulus
    c0 = v%mat%c0
    s = v%mat%s
    gamma0 = v%mat%gamma0
    shear_modulus = v%mat%shear_modulus
    youngs_modulus = v%mat%youngs_modulus
    poisson_ratio = v%mat%poisson_ratio
    yield_stress = v%mat%yield_stress
    hardening_modulus = v%mat%hardening_modulus
    jc_a = v%mat%jc_a
    jc_b = v%mat%jc_b
    jc_n = v%mat%jc_n
    jc_c = v%mat%jc_c
    jc_m = v%mat%jc_m
    jc_rate0 = v%mat%jc_rate0
    t_melt = v%mat%t_melt
    t_room = v%mat%t_room
    specific_heat = v%mat%specific_heat
    taylor_quinney = v%mat%taylor_quinney
    initial_temperature = v%mat%initial_temperature
    read(text, nml=material, iostat=ios, iomsg=msg)
    if (ios /= 0) return
    v%mat%name = name
    v%eos = eos
    v%strength = strength
    v%mat%rho0 = rho0
    v%mat%bulk_modulus = bulk_modulus
    v%mat%c0 = c0
    v%mat%s = s
    v%mat%gamma0 = gamma0
    v%mat%shear_modulus = shear_modulus
    v%mat%youngs_modulus = youngs_modulus
    v%mat%poisson_ratio = poisson_ratio
    v%mat%yield_stress = yield_stress
    v%mat%hardening_modulus = hardening_modulus
    v%mat%jc_a = jc_a
    v%mat%jc_b = jc_b
    v%mat%jc_n = jc_n
    v%mat%jc_c = jc_c
    v%mat%jc_m = jc_m
    v%mat%jc_rate0 = jc_rate0
    v%mat%t_melt = t_melt
    v%mat%t_room = t_room
    v%mat%specific_heat = specific_heat
    v%mat%taylor_quinney = taylor_quinney
    v%mat%initial_temperature = initial_temperature
  end subroutine nml_material

  subroutine nml_part(text, v, ios, msg)
    character(len=*), intent(in) :: text
    type(values_t), intent(inout) :: v
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    character(len=max_name_len) :: group, material
    real(rk) :: velocity(3)
    namelist /part/ group, material, velocity
    group = v%part%group
    material = v%part%material
    velocity = v%part%velocity
    read(text, nml=part, iostat=ios, iomsg=msg)
    if (ios /= 0) return
    v%part%group = group
    v%part%material = material
    v%part%velocity = velocity
  end subroutine nml_part

  subroutine nml_boundary(text, v, ios, msg)
    character(len=*), intent(in) :: text
    type(values_t), intent(inout) :: v
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    character(len=code_len) :: kind, wall_type
    character(len=max_name_len) :: surface
    real(rk) :: point(3), normal(3)
    namelist /boundary/ kind, surface, point, normal, wall_type
    kind = v%kind
    wall_type = v%wall_type
    surface = v%bnd%surface
    point = v%bnd%point
    normal = v%bnd%normal
    read(text, nml=boundary, iostat=ios, iomsg=msg)
    if (ios /= 0) return
    v%kind = kind
    v%wall_type = wall_type
    v%bnd%surface = surface
    v%bnd%point = point
    v%bnd%normal = normal
  end subroutine nml_boundary

  subroutine nml_numerics(text, v, ios, msg)
    character(len=*), intent(in) :: text
    type(values_t), intent(inout) :: v
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    logical :: anti_locking
    real(rk) :: q_linear, q_quadratic
    namelist /numerics/ anti_locking, q_linear, q_quadratic
    anti_locking = v%num%anti_locking
    q_linear = v%num%q_linear
    q_quadratic = v%num%q_quadratic
    read(text, nml=numerics, iostat=ios, iomsg=msg)
    if (ios /= 0) return
    v%num%anti_locking = anti_locking
    v%num%q_linear = q_linear
    v%num%q_quadratic = q_quadratic
  end subroutine nml_numerics

  subroutine nml_output(text, v, ios, msg)
    character(len=*), intent(in) :: text
    type(values_t), intent(inout) :: v
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: msg
    character(len=max_path_len) :: directory
    character(len=max_name_len) :: case_name
    real(rk) :: dt_field, dt_history
    namelist /output/ directory, case_name, dt_field, dt_history
    directory = v%out%directory
    case_name = v%out%case_name
    dt_field = v%out%dt_field
    dt_history = v%out%dt_history
    read(text, nml=output, iostat=ios, iomsg=msg)
    if (ios /= 0) return
    v%out%directory = directory
    v%out%case_name = case_name
    v%out%dt_field = dt_field
    v%out%dt_history = dt_history
  end subroutine nml_output

  ! ======================================================================
  !  checks
  ! ======================================================================

  subroutine check_run(ctx, inst, r)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(run_cfg_t), intent(in) :: r
    call need(ctx, inst, 't_end', positive(r%t_end), '> 0', 's')
    call need(ctx, inst, 'dt_safety', inside(r%dt_safety, 0.0_rk, 1.0_rk) .or. r%dt_safety == 1, &
         'in (0, 1]', '-')
    call need(ctx, inst, 'dt_initial', nonneg(r%dt_initial), '>= 0', 's')
    call need(ctx, inst, 'dt_max', positive(r%dt_max), '> 0', 's')
    call need(ctx, inst, 'max_cycles', r%max_cycles >= 1, '>= 1', '')
    call need(ctx, inst, 'cycle_print', r%cycle_print >= 1, '>= 1', '')
    call need(ctx, inst, 'energy_error_limit', positive(r%energy_error_limit), '> 0', '-')
    call need(ctx, inst, 'wall_limit', nonneg(r%wall_limit), '>= 0', 's')
    if (positive(r%dt_initial) .and. positive(r%dt_max) .and. r%dt_initial > r%dt_max) &
         call complain(ctx, inst, 'dt_initial', 'larger than dt_max = '//r2s(r%dt_max)//' s')
  end subroutine check_run

  !> Besides the ranges: the mesh file must exist; a relative name is taken
  !> from the deck's folder, and the absolute path is stored in m%file.
  subroutine check_mesh(ctx, inst, m, deck_path)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(mesh_cfg_t), intent(inout) :: m
    character(len=*), intent(in) :: deck_path
    character(len=:), allocatable :: f
    logical :: exists

    call need(ctx, inst, 'scale', positive(m%scale), '> 0 (e.g. 0.001 for a mesh in mm)', '-')
    if (is_bad(inst, 'file')) return
    if (len_trim(m%file) == 0) then
      call need(ctx, inst, 'file', .false., "the gmsh mesh file, e.g. 'target.msh'", '')
      return
    end if
    f = trim(m%file)
    if (f(1:1) /= '/') f = dir_of(deck_path)//f
    inquire(file=f, exist=exists)
    if (.not. exists) then
      call complain(ctx, inst, 'file', "mesh file not found (looked for '"//f// &
           "'; a relative name is taken from the deck's folder)")
      return
    end if
    m%file = absolute_path(f)
  end subroutine check_mesh

  !> Material models: ranges, what each EOS / strength model needs, parameters
  !> set for a model that is not selected, and the derived elastic moduli.
  subroutine check_material(ctx, inst, m, eos_txt, str_txt, earlier, earlier_inst)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(material_cfg_t), intent(inout) :: m
    character(len=*), intent(in) :: eos_txt, str_txt
    type(material_cfg_t), intent(in) :: earlier(:)
    type(inst_t), intent(in) :: earlier_inst(:)

    logical :: eos_ok, str_ok, e_set, nu_set, en_ok, plastic, elastic_needed
    real(rk) :: k_en, g_en, k_mg
    character(len=:), allocatable :: sname
    integer :: j

    ! name: present and unique (names are compared without regard to case)
    if (.not. is_bad(inst, 'name')) then
      if (len_trim(m%name) == 0) then
        call need(ctx, inst, 'name', .false., 'a name that &part groups refer to', '')
      else
        do j = 1, size(earlier)
          if (nml_lower(trim(earlier(j)%name)) == nml_lower(trim(m%name))) then
            call complain(ctx, inst, 'name', "the name is already used by &material #"// &
                 itoa(j)//' (line '//itoa(earlier_inst(j)%line)//')')
            exit
          end if
        end do
      end if
    end if

    call need(ctx, inst, 'rho0', positive(m%rho0), '> 0', 'kg/m3')

    eos_ok = choice(ctx, inst, 'eos', eos_txt, eos_words, eos_codes, m%eos)
    str_ok = choice(ctx, inst, 'strength', str_txt, strength_words, strength_codes, m%strength)

    ! Young's modulus and Poisson's ratio: optional, but only as a pair
    ! (an unreadable value counts as given: it has been reported already)
    e_set = m%youngs_modulus /= mat_dflt%youngs_modulus .or. is_bad(inst, 'youngs_modulus')
    nu_set = m%poisson_ratio /= mat_dflt%poisson_ratio .or. is_bad(inst, 'poisson_ratio')
    if (e_set) call need(ctx, inst, 'youngs_modulus', positive(m%youngs_modulus), '> 0', 'Pa')
    if (nu_set) call need(ctx, inst, 'poisson_ratio', &
         inside(m%poisson_ratio, -1.0_rk, 0.5_rk), 'in (-1, 0.5)', '-')
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
          call need(ctx, inst, 'bulk_modulus', positive(m%bulk_modulus), '> 0', 'Pa')
          if (en_ok .and. positive(m%bulk_modulus)) then
            if (differs(m%bulk_modulus, k_en)) call complain(ctx, inst, 'bulk_modulus', &
                 'disagrees with youngs_modulus and poisson_ratio, which give E/(3(1-2nu)) = '// &
                 r2s(k_en)//' Pa: give one or the other')
          end if
        else if (en_ok) then
          m%bulk_modulus = k_en
        else if (.not. (e_set .or. nu_set)) then
          call need(ctx, inst, 'bulk_modulus', .false., &
               "> 0 for eos = 'linear' (or give youngs_modulus and poisson_ratio)", 'Pa')
        end if
      case (eos_mie_gruneisen)
        call need(ctx, inst, 'c0', positive(m%c0), "> 0 for eos = 'mie_gruneisen'", 'm/s')
        call need(ctx, inst, 's', nonneg(m%s), '>= 0', '-')
        call need(ctx, inst, 'gamma0', nonneg(m%gamma0), '>= 0', '-')
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
        end if
      end select
      if (m%eos /= eos_mie_gruneisen) then
        call unused(ctx, inst, 'c0', m%c0 /= mat_dflt%c0, "eos = 'mie_gruneisen'")
        call unused(ctx, inst, 's', m%s /= mat_dflt%s, "eos = 'mie_gruneisen'")
        call unused(ctx, inst, 'gamma0', m%gamma0 /= mat_dflt%gamma0, "eos = 'mie_gruneisen'")
      end if
    end if

    ! shear modulus
    elastic_needed = str_ok .and. m%strength /= strength_none
    if (m%shear_modulus /= mat_dflt%shear_modulus) then
      if (str_ok .and. m%strength == strength_none) then
        call need(ctx, inst, 'shear_modulus', nonneg(m%shear_modulus), '>= 0', 'Pa')
      else
        call need(ctx, inst, 'shear_modulus', positive(m%shear_modulus), '> 0', 'Pa')
      end if
      if (en_ok .and. positive(m%shear_modulus)) then
        if (differs(m%shear_modulus, g_en)) call complain(ctx, inst, 'shear_modulus', &
             'disagrees with youngs_modulus and poisson_ratio, which give E/(2(1+nu)) = '// &
             r2s(g_en)//' Pa: give one or the other')
      end if
    else if (en_ok) then
      m%shear_modulus = g_en
    else if (elastic_needed .and. .not. (e_set .or. nu_set)) then
      call need(ctx, inst, 'shear_modulus', .false., "> 0 for strength = '"// &
           trim(str_txt)//"' (or give youngs_modulus and poisson_ratio)", 'Pa')
    else if (str_ok .and. m%strength == strength_none) then
      m%shear_modulus = 0     ! a fluid: the solver reads 0
    end if

    ! plasticity
    if (str_ok) then
      sname = "strength = '"//trim(strength_words(findloc(strength_codes, m%strength, 1)))//"'"
      plastic = m%strength == strength_perfectly_plastic .or. m%strength == strength_linear_hardening
      if (plastic) then
        call need(ctx, inst, 'yield_stress', positive(m%yield_stress), '> 0 for '//sname, 'Pa')
      else if (m%strength == strength_johnson_cook) then
        call unused(ctx, inst, 'yield_stress', m%yield_stress /= mat_dflt%yield_stress, &
             "'perfectly_plastic' or 'linear_hardening' (Johnson-Cook takes jc_a)")
      else
        call unused(ctx, inst, 'yield_stress', m%yield_stress /= mat_dflt%yield_stress, &
             "strength = 'perfectly_plastic', 'linear_hardening' or 'johnson_cook' (jc_a)")
      end if
      if (m%strength == strength_linear_hardening) then
        call need(ctx, inst, 'hardening_modulus', nonneg(m%hardening_modulus), '>= 0', 'Pa')
      else
        call unused(ctx, inst, 'hardening_modulus', &
             m%hardening_modulus /= mat_dflt%hardening_modulus, "strength = 'linear_hardening'")
      end if
      if (m%strength == strength_johnson_cook) then
        call need(ctx, inst, 'jc_a', positive(m%jc_a), '> 0 for '//sname, 'Pa')
        call need(ctx, inst, 'jc_b', nonneg(m%jc_b), '>= 0', 'Pa')
        call need(ctx, inst, 'jc_n', positive(m%jc_n), '> 0', '-')
        call need(ctx, inst, 'jc_c', nonneg(m%jc_c), '>= 0', '-')
        call need(ctx, inst, 'jc_m', positive(m%jc_m), '> 0', '-')
        call need(ctx, inst, 'jc_rate0', positive(m%jc_rate0), '> 0', '1/s')
        call need(ctx, inst, 'specific_heat', positive(m%specific_heat), &
             '> 0 for '//sname//' (thermal softening)', 'J/(kg K)')
        if (.not. is_bad(inst, 't_room')) then
          call need(ctx, inst, 't_melt', positive(m%t_melt) .and. positive(m%t_room) .and. &
               m%t_melt > m%t_room, &
               '> t_room = '//r2s(m%t_room)//' K for '//sname, 'K')
        end if
      else
        call unused(ctx, inst, 'jc_a', m%jc_a /= mat_dflt%jc_a, "strength = 'johnson_cook'")
        call unused(ctx, inst, 'jc_b', m%jc_b /= mat_dflt%jc_b, "strength = 'johnson_cook'")
        call unused(ctx, inst, 'jc_n', m%jc_n /= mat_dflt%jc_n, "strength = 'johnson_cook'")
        call unused(ctx, inst, 'jc_c', m%jc_c /= mat_dflt%jc_c, "strength = 'johnson_cook'")
        call unused(ctx, inst, 'jc_m', m%jc_m /= mat_dflt%jc_m, "strength = 'johnson_cook'")
        call unused(ctx, inst, 'jc_rate0', m%jc_rate0 /= mat_dflt%jc_rate0, &
             "strength = 'johnson_cook'")
      end if
    end if

    ! thermal data (also used for output when the model does not need it)
    if (m%specific_heat /= mat_dflt%specific_heat) &
         call need(ctx, inst, 'specific_heat', positive(m%specific_heat), '> 0', 'J/(kg K)')
    if (m%t_melt /= mat_dflt%t_melt) &
         call need(ctx, inst, 't_melt', positive(m%t_melt), '> 0', 'K')
    call need(ctx, inst, 't_room', positive(m%t_room), '> 0', 'K')
    call need(ctx, inst, 'taylor_quinney', nonneg(m%taylor_quinney) .and. m%taylor_quinney <= 1, &
         'in [0, 1]', '-')
    call need(ctx, inst, 'initial_temperature', positive(m%initial_temperature), '> 0', 'K')
  end subroutine check_material

  !> A part names a mesh volume group and a defined material.
  subroutine check_part(ctx, inst, p, earlier, earlier_inst, mats, nmat)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(part_cfg_t), intent(inout) :: p
    type(part_cfg_t), intent(in) :: earlier(:)
    type(inst_t), intent(in) :: earlier_inst(:)
    type(material_cfg_t), intent(in) :: mats(:)
    integer, intent(in) :: nmat
    character(len=:), allocatable :: names
    integer :: j, found

    if (.not. is_bad(inst, 'group')) then
      if (len_trim(p%group) == 0) then
        call need(ctx, inst, 'group', .false., 'the name of a physical volume group in the mesh', '')
      else
        do j = 1, size(earlier)
          if (earlier(j)%group == p%group) then
            call complain(ctx, inst, 'group', 'the same mesh group is already used by &part #'// &
                 itoa(j)//' (line '//itoa(earlier_inst(j)%line)//')')
            exit
          end if
        end do
      end if
    end if

    if (.not. is_bad(inst, 'material')) then
      names = ''
      do j = 1, nmat
        if (len_trim(mats(j)%name) == 0) cycle
        if (len(names) > 0) names = names//', '
        names = names//"'"//trim(mats(j)%name)//"'"
      end do
      if (len(names) == 0) names = 'none'
      if (len_trim(p%material) == 0) then
        call need(ctx, inst, 'material', .false., 'the name of a &material (defined: '// &
             names//')', '')
      else
        found = 0
        do j = 1, nmat
          if (nml_lower(trim(mats(j)%name)) == nml_lower(trim(p%material))) then
            found = j
            exit
          end if
        end do
        if (found == 0) then
          call complain(ctx, inst, 'material', 'no &material of that name (defined: '//names//')')
        else
          p%material = mats(found)%name    ! the material's own spelling
        end if
      end if
    end if

    call need(ctx, inst, 'velocity', all(ieee_is_finite(p%velocity)), 'finite numbers', 'm/s')
  end subroutine check_part

  subroutine check_boundary(ctx, inst, b, kind_txt, wall_txt)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(boundary_cfg_t), intent(inout) :: b
    character(len=*), intent(in) :: kind_txt, wall_txt
    logical :: kind_ok, wall_ok
    real(rk) :: nrm

    if (len_trim(kind_txt) == 0 .and. .not. is_bad(inst, 'kind')) then
      call need(ctx, inst, 'kind', .false., 'one of '//word_list(kind_words), '')
      kind_ok = .false.
    else
      kind_ok = choice(ctx, inst, 'kind', kind_txt, kind_words, kind_codes, b%kind)
    end if
    wall_ok = choice(ctx, inst, 'wall_type', wall_txt, wall_words, wall_codes, b%wall_type)
    call need(ctx, inst, 'point', all(ieee_is_finite(b%point)), 'finite numbers', 'm')
    call need(ctx, inst, 'normal', all(ieee_is_finite(b%normal)), 'finite numbers', '-')
    if (.not. kind_ok) return

    select case (b%kind)
    case (bc_fixed, bc_symmetry)
      if (len_trim(b%surface) == 0) call need(ctx, inst, 'surface', .false., &
           "the name of a physical surface group in the mesh, for kind = '"//trim(kind_txt)//"'", '')
      if (wall_ok) call unused(ctx, inst, 'wall_type', b%wall_type /= bnd_dflt%wall_type, &
           "kind = 'rigid_wall'")
    case (bc_rigid_wall)
      if (all(ieee_is_finite(b%normal)) .and. .not. is_bad(inst, 'normal')) then
        nrm = norm2(b%normal)
        if (nrm > 0) then
          ! normalise; a vector already of unit length is kept bit for bit
          if (abs(nrm - 1) > 8 * epsilon(1.0_rk)) b%normal = b%normal / nrm
        else
          call need(ctx, inst, 'normal', .false., &
               "a non-zero vector for kind = 'rigid_wall' (pointing towards the bodies)", '-')
        end if
      end if
    end select
  end subroutine check_boundary

  subroutine check_numerics(ctx, inst, n)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(numerics_cfg_t), intent(in) :: n
    call need(ctx, inst, 'q_linear', nonneg(n%q_linear), '>= 0', '-')
    call need(ctx, inst, 'q_quadratic', nonneg(n%q_quadratic), '>= 0', '-')
  end subroutine check_numerics

  subroutine check_output(ctx, inst, o, deck_path)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    type(output_cfg_t), intent(inout) :: o
    character(len=*), intent(in) :: deck_path
    call need(ctx, inst, 'dt_field', nonneg(o%dt_field), '>= 0', 's')
    call need(ctx, inst, 'dt_history', nonneg(o%dt_history), '>= 0', 's')
    if (len_trim(o%directory) == 0) call need(ctx, inst, 'directory', .false., &
         "a folder name ('.' = the current folder)", '')
    if (len_trim(o%case_name) == 0 .and. .not. is_set(inst, 'case_name')) then
      o%case_name = stem_of(deck_path)
    else if (len_trim(o%case_name) == 0) then
      call need(ctx, inst, 'case_name', .false., 'a non-empty name for the output files', '')
    end if
  end subroutine check_output

  ! ---------------------------------------------------------- check helpers

  !> Report name unless ok: "name = value : must be RULE (UNIT)" where the deck
  !> set it, "name is required: RULE (UNIT)" where it did not. Silent for
  !> variables that could not be read (already reported).
  subroutine need(ctx, inst, name, ok, rule, unit)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    character(len=*), intent(in) :: name
    logical, intent(in) :: ok
    character(len=*), intent(in) :: rule, unit
    character(len=:), allocatable :: u
    integer :: k
    if (ok .or. is_bad(inst, name)) return
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

  !> A parameter set for a model that is not selected: likely a forgotten switch.
  subroutine unused(ctx, inst, name, is_given, used_by)
    type(ctx_t), intent(inout) :: ctx
    type(inst_t), intent(in) :: inst
    character(len=*), intent(in) :: name, used_by
    logical, intent(in) :: is_given
    if (.not. is_given) return
    call complain(ctx, inst, name, 'set, but only used with '//used_by// &
         ': select that model or remove the line')
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
    w = nml_lower(trim(adjustl(txt)))
    do j = 1, size(words)
      if (w == trim(words(j))) then
        code = codes(j)
        ok = .true.
        return
      end if
    end do
    call complain(ctx, inst, name, 'unknown choice; valid: '//word_list(words)// &
         suggestion(w, words, "'", "'"))
  end function choice

  ! (finite first: no ordered comparison with NaN)
  pure logical function positive(x)
    real(rk), intent(in) :: x
    positive = .false.
    if (ieee_is_finite(x)) positive = x > 0
  end function positive

  pure logical function nonneg(x)
    real(rk), intent(in) :: x
    nonneg = .false.
    if (ieee_is_finite(x)) nonneg = x >= 0
  end function nonneg

  !> x in the open interval (lo, hi).
  pure logical function inside(x, lo, hi)
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
    type(inst_t) :: none, i_run, i_mesh, i_num, i_out
    integer :: k
    logical :: tracked

    ! copies, so that the optional track is only touched when present
    tracked = present(tr)
    if (tracked) then
      i_run = tr%run
      i_mesh = tr%mesh
      i_num = tr%numerics
      i_out = tr%output
    end if
    text = '! udar resolved input deck'//nl
    if (len_trim(cfg%deck_file) > 0) text = text//'! from: '//trim(cfg%deck_file)//nl
    if (tracked) then
      text = text//'! (default) = not set in the deck, (derived) = computed from other values,'//nl
      text = text//'! (not set) = not given and not needed'//nl
    else
      text = text//'! (default) = the built-in default value'//nl
    end if

    text = text//nl//'&run'//nl
    associate(r => cfg%run, d => run_dflt)
      call put(text, i_run, tracked, 'title', qs(r%title), '', r%title == d%title)
      call put(text, i_run, tracked, 't_end', r2s(r%t_end), 's', r%t_end == d%t_end)
      call put(text, i_run, tracked, 'dt_safety', r2s(r%dt_safety), '-', &
               r%dt_safety == d%dt_safety)
      call put(text, i_run, tracked, 'dt_initial', r2s(r%dt_initial), 's', &
               r%dt_initial == d%dt_initial)
      call put(text, i_run, tracked, 'dt_max', r2s(r%dt_max), 's', r%dt_max == d%dt_max)
      call put(text, i_run, tracked, 'max_cycles', itoa(r%max_cycles), '-', &
               r%max_cycles == d%max_cycles)
      call put(text, i_run, tracked, 'cycle_print', itoa(r%cycle_print), '-', &
               r%cycle_print == d%cycle_print)
      call put(text, i_run, tracked, 'energy_error_limit', r2s(r%energy_error_limit), '-', &
               r%energy_error_limit == d%energy_error_limit)
      call put(text, i_run, tracked, 'wall_limit', r2s(r%wall_limit), 's', &
               r%wall_limit == d%wall_limit)
    end associate
    text = text//'/'//nl

    text = text//nl//'&mesh'//nl
    call put(text, i_mesh, tracked, 'file', qs(cfg%mesh%file), '', &
             cfg%mesh%file == mesh_dflt%file)
    call put(text, i_mesh, tracked, 'scale', r2s(cfg%mesh%scale), '-', &
             cfg%mesh%scale == mesh_dflt%scale)
    text = text//'/'//nl

    if (allocated(cfg%materials)) then
      do k = 1, size(cfg%materials)
        if (tracked) then
          call put_material(text, cfg%materials(k), tr%materials(k), .true.)
        else
          call put_material(text, cfg%materials(k), none, .false.)
        end if
      end do
    end if

    if (allocated(cfg%parts)) then
      do k = 1, size(cfg%parts)
        associate(p => cfg%parts(k), d => part_dflt)
          text = text//nl//'&part'//nl
          if (tracked) then
            call put(text, tr%parts(k), .true., 'group', qs(p%group), '', p%group == d%group)
            call put(text, tr%parts(k), .true., 'material', qs(p%material), '', &
                     p%material == d%material)
            call put(text, tr%parts(k), .true., 'velocity', r2s_list(p%velocity), 'm/s', &
                     all(p%velocity == d%velocity))
          else
            call put(text, none, .false., 'group', qs(p%group), '', p%group == d%group)
            call put(text, none, .false., 'material', qs(p%material), '', p%material == d%material)
            call put(text, none, .false., 'velocity', r2s_list(p%velocity), 'm/s', &
                     all(p%velocity == d%velocity))
          end if
          text = text//'/'//nl
        end associate
      end do
    end if

    if (allocated(cfg%boundaries)) then
      do k = 1, size(cfg%boundaries)
        if (tracked) then
          call put_boundary(text, cfg%boundaries(k), tr%boundaries(k), .true.)
        else
          call put_boundary(text, cfg%boundaries(k), none, .false.)
        end if
      end do
    end if

    text = text//nl//'&numerics'//nl
    associate(n => cfg%numerics, d => num_dflt)
      call put(text, i_num, tracked, 'anti_locking', ltoa(n%anti_locking), '', &
               n%anti_locking .eqv. d%anti_locking)
      call put(text, i_num, tracked, 'q_linear', r2s(n%q_linear), '-', &
               n%q_linear == d%q_linear)
      call put(text, i_num, tracked, 'q_quadratic', r2s(n%q_quadratic), '-', &
               n%q_quadratic == d%q_quadratic)
    end associate
    text = text//'/'//nl

    text = text//nl//'&output'//nl
    associate(o => cfg%output, d => out_dflt)
      call put(text, i_out, tracked, 'directory', qs(o%directory), '', &
               o%directory == d%directory)
      call put(text, i_out, tracked, 'case_name', qs(o%case_name), '', &
               o%case_name == d%case_name, 'the deck file name')
      call put(text, i_out, tracked, 'dt_field', r2s(o%dt_field), 's', &
               o%dt_field == d%dt_field)
      call put(text, i_out, tracked, 'dt_history', r2s(o%dt_history), 's', &
               o%dt_history == d%dt_history)
    end associate
    text = text//'/'//nl

  end subroutine write_resolved

  subroutine put_material(text, m, inst, tracked)
    character(len=:), allocatable, intent(inout) :: text
    type(material_cfg_t), intent(in) :: m
    type(inst_t), intent(in) :: inst
    logical, intent(in) :: tracked
    character(len=:), allocatable :: from_en
    associate(d => mat_dflt)
      if (m%eos == eos_mie_gruneisen) then
        from_en = 'rho0*c0**2'
      else
        from_en = 'youngs_modulus, poisson_ratio'
      end if
      text = text//nl//'&material'//nl
      call put(text, inst, tracked, 'name', qs(m%name), '', m%name == d%name)
      call put(text, inst, tracked, 'rho0', r2s(m%rho0), 'kg/m3', m%rho0 == d%rho0)
      call put(text, inst, tracked, 'eos', qs(code_word(m%eos, eos_words, eos_codes)), &
               'linear | mie_gruneisen', m%eos == d%eos)
      call put(text, inst, tracked, 'bulk_modulus', r2s(m%bulk_modulus), 'Pa', &
               m%bulk_modulus == d%bulk_modulus, from_en)
      call put(text, inst, tracked, 'c0', r2s(m%c0), 'm/s', m%c0 == d%c0)
      call put(text, inst, tracked, 's', r2s(m%s), '-', m%s == d%s)
      call put(text, inst, tracked, 'gamma0', r2s(m%gamma0), '-', m%gamma0 == d%gamma0)
      call put(text, inst, tracked, 'strength', &
               qs(code_word(m%strength, strength_words, strength_codes)), &
               'none | elastic | perfectly_plastic | linear_hardening | johnson_cook', &
               m%strength == d%strength)
      call put(text, inst, tracked, 'shear_modulus', r2s(m%shear_modulus), 'Pa', &
               m%shear_modulus == d%shear_modulus, 'youngs_modulus, poisson_ratio')
      call put(text, inst, tracked, 'youngs_modulus', r2s(m%youngs_modulus), 'Pa', &
               m%youngs_modulus == d%youngs_modulus)
      call put(text, inst, tracked, 'poisson_ratio', r2s(m%poisson_ratio), '-', &
               m%poisson_ratio == d%poisson_ratio)
      call put(text, inst, tracked, 'yield_stress', r2s(m%yield_stress), 'Pa', &
               m%yield_stress == d%yield_stress)
      call put(text, inst, tracked, 'hardening_modulus', r2s(m%hardening_modulus), 'Pa', &
               m%hardening_modulus == d%hardening_modulus)
      call put(text, inst, tracked, 'jc_a', r2s(m%jc_a), 'Pa', m%jc_a == d%jc_a)
      call put(text, inst, tracked, 'jc_b', r2s(m%jc_b), 'Pa', m%jc_b == d%jc_b)
      call put(text, inst, tracked, 'jc_n', r2s(m%jc_n), '-', m%jc_n == d%jc_n)
      call put(text, inst, tracked, 'jc_c', r2s(m%jc_c), '-', m%jc_c == d%jc_c)
      call put(text, inst, tracked, 'jc_m', r2s(m%jc_m), '-', m%jc_m == d%jc_m)
      call put(text, inst, tracked, 'jc_rate0', r2s(m%jc_rate0), '1/s', m%jc_rate0 == d%jc_rate0)
      call put(text, inst, tracked, 't_melt', r2s(m%t_melt), 'K', m%t_melt == d%t_melt)
      call put(text, inst, tracked, 't_room', r2s(m%t_room), 'K', m%t_room == d%t_room)
      call put(text, inst, tracked, 'specific_heat', r2s(m%specific_heat), 'J/(kg K)', &
               m%specific_heat == d%specific_heat)
      call put(text, inst, tracked, 'taylor_quinney', r2s(m%taylor_quinney), '-', &
               m%taylor_quinney == d%taylor_quinney)
      call put(text, inst, tracked, 'initial_temperature', r2s(m%initial_temperature), 'K', &
               m%initial_temperature == d%initial_temperature)
    end associate
    text = text//'/'//nl
  end subroutine put_material

  subroutine put_boundary(text, b, inst, tracked)
    character(len=:), allocatable, intent(inout) :: text
    type(boundary_cfg_t), intent(in) :: b
    type(inst_t), intent(in) :: inst
    logical, intent(in) :: tracked
    associate(d => bnd_dflt)
      text = text//nl//'&boundary'//nl
      call put(text, inst, tracked, 'kind', qs(code_word(b%kind, kind_words, kind_codes)), &
               'fixed | symmetry | rigid_wall', b%kind == d%kind)
      call put(text, inst, tracked, 'surface', qs(b%surface), '', b%surface == d%surface)
      call put(text, inst, tracked, 'point', r2s_list(b%point), 'm', all(b%point == d%point))
      call put(text, inst, tracked, 'normal', r2s_list(b%normal), '-', all(b%normal == d%normal))
      call put(text, inst, tracked, 'wall_type', qs(code_word(b%wall_type, wall_words, wall_codes)), &
               'frictionless | sticking', b%wall_type == d%wall_type)
    end associate
    text = text//'/'//nl
  end subroutine put_boundary

  !> One "  name = value   ! unit (marker)" line.
  subroutine put(text, inst, tracked, name, value, unit, at_default, derived_from)
    character(len=:), allocatable, intent(inout) :: text
    type(inst_t), intent(in) :: inst
    logical, intent(in) :: tracked
    character(len=*), intent(in) :: name, value, unit
    logical, intent(in) :: at_default
    character(len=*), intent(in), optional :: derived_from
    character(len=:), allocatable :: line, note
    integer, parameter :: comment_col = 40

    note = ''
    if (tracked) then
      if (.not. is_set(inst, name)) then
        if (at_default .and. value == '-1.0') then
          note = '(not set)'          ! -1 is the "not given" value in udar_config
        else if (at_default) then
          note = '(default)'
        else if (present(derived_from)) then
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

    grp = nml_lower(trim(group))
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
    if (present(variable)) k = last_assign(inst, nml_lower(trim(variable)))
    if (k > 0) then
      where = trim(cfg%deck_file)//':'//itoa(inst%a(k)%line)//': '//prefix(inst)// &
              trim(variable)//' = '//as_single_quoted(inst%a(k)%value)
    else
      where = trim(cfg%deck_file)
      if (inst%line > 0) where = where//':'//itoa(inst%line)
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
    inst%na = 0
    if (allocated(inst%a)) deallocate(inst%a)
    allocate(inst%a(8))
  end subroutine init_inst

  subroutine inst_add(inst, base, value, line)
    type(inst_t), intent(inout) :: inst
    character(len=*), intent(in) :: base, value
    integer, intent(in) :: line
    type(asg_t), allocatable :: tmp(:)
    if (inst%na == size(inst%a)) then
      allocate(tmp(2*size(inst%a)))
      tmp(1:inst%na) = inst%a(1:inst%na)
      call move_alloc(tmp, inst%a)
    end if
    inst%na = inst%na + 1
    inst%a(inst%na)%base = base
    inst%a(inst%na)%value = value
    inst%a(inst%na)%line = line
    inst%a(inst%na)%bad = .false.
  end subroutine inst_add

  !> Index of the last assignment to name (base name, any subscript), 0 if none.
  pure integer function last_assign(inst, name) result(k)
    type(inst_t), intent(in) :: inst
    character(len=*), intent(in) :: name
    do k = inst%na, 1, -1
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
    integer :: k
    is_bad = .false.
    do k = 1, inst%na
      if (inst%a(k)%base == name .and. inst%a(k)%bad) is_bad = .true.
    end do
  end function is_bad

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
  !> mesh group, the boundary's surface or kind (as written in the deck).
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
    case default
      keys = ''
    end select
    label = ''
    do j = 1, 2
      if (len_trim(keys(j)) == 0) cycle
      do k = gr%n_assign, 1, -1
        if (gr%assigns(k)%base == trim(keys(j)) .and. gr%assigns(k)%ok) then
          label = shorten(leading_string(gr%assigns(k)%value), 40)
          if (len(label) > 0) return
        end if
      end do
    end do
  end function instance_label

  subroutine report(ctx, line, text)
    type(ctx_t), intent(inout) :: ctx
    integer, intent(in) :: line
    character(len=*), intent(in) :: text
    type(diag_t), allocatable :: tmp(:)
    if (ctx%n == size(ctx%d)) then
      allocate(tmp(2*size(ctx%d)))
      tmp(1:ctx%n) = ctx%d(1:ctx%n)
      call move_alloc(tmp, ctx%d)
    end if
    ctx%n = ctx%n + 1
    ctx%d(ctx%n)%line = line
    if (line > 0) then
      ctx%d(ctx%n)%text = ctx%path//':'//itoa(line)//': '//text
    else
      ctx%d(ctx%n)%text = ctx%path//': '//text
    end if
  end subroutine report

  !> Stable insertion sort by line (deck-wide messages, line 0, first).
  subroutine sort_diags(ctx)
    type(ctx_t), intent(inout) :: ctx
    type(diag_t) :: t
    integer :: i, j
    do i = 2, ctx%n
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

  !> Variable names of group grp, all (typ = '*') or of one type, in table order.
  subroutine group_var_names(grp, typ, names)
    character(len=*), intent(in) :: grp
    character, intent(in) :: typ
    character(len=20), allocatable, intent(out) :: names(:)
    logical :: sel(size(vars))
    integer :: iv, n
    sel = vars%grp == grp .and. (vars%typ == typ .or. typ == '*')
    allocate(names(count(sel)))
    n = 0
    do iv = 1, size(vars)
      if (.not. sel(iv)) cycle
      n = n + 1
      names(n) = vars(iv)%name
    end do
  end subroutine group_var_names

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
    if (len(s) == 0) s = ' (groups: '//word_list(group_names, '&')//')'
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

    call group_var_names(grp, '*', names)
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
      s = s//' (valid: '//word_list(names)//')'
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
      if (var_index(grp, nml_lower(value(i:j-1))) > 0) then
        word = nml_lower(value(i:j-1))
        return
      end if
      i = j
    end do
  end function known_word_in

  !> "'a', 'b', 'c'" (or "&a, &b" with open='&').
  function word_list(words, open) result(s)
    character(len=*), intent(in) :: words(:)
    character(len=*), intent(in), optional :: open
    character(len=:), allocatable :: s
    integer :: j
    s = ''
    do j = 1, size(words)
      if (j > 1) s = s//', '
      if (present(open)) then
        s = s//open//trim(words(j))
      else
        s = s//"'"//trim(words(j))//"'"
      end if
    end do
  end function word_list

  function code_word(code, words, codes) result(w)
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

  !> A namelist string value without its quotes ('' if it is not one string).
  pure function unquote(v) result(s)
    character(len=*), intent(in) :: v
    character(len=:), allocatable :: s
    character :: q
    integer :: i
    s = ''
    if (len(v) < 2) return
    q = v(1:1)
    if ((q /= "'" .and. q /= '"') .or. v(len(v):len(v)) /= q) return
    i = 2
    do while (i < len(v))
      s = s//v(i:i)
      if (v(i:i) == q) i = i + 1     ! doubled quote
      i = i + 1
    end do
  end function unquote

  !> The first quoted string of a value, without quotes ('' if it does not
  !> start with one): names a group instance even when the value is broken.
  pure function leading_string(v) result(s)
    character(len=*), intent(in) :: v
    character(len=:), allocatable :: s
    character :: q
    integer :: i
    s = ''
    if (len(v) < 2) return
    q = v(1:1)
    if (q /= "'" .and. q /= '"') return
    i = 2
    do while (i <= len(v))
      if (v(i:i) == q) then
        if (i == len(v)) return
        if (v(i+1:i+1) /= q) return
        i = i + 1                    ! doubled quote
      end if
      s = s//v(i:i)
      i = i + 1
    end do
  end function leading_string

  !> A value that is one string, written with single quotes ("rod" -> 'rod');
  !> any other value unchanged.
  pure function as_single_quoted(v) result(s)
    character(len=*), intent(in) :: v
    character(len=:), allocatable :: s
    s = v
    if (len(v) < 2) return
    if ((v(1:1) == '"' .or. v(1:1) == "'") .and. v(len(v):len(v)) == v(1:1)) then
      if (qs(unquote(v)) /= qs(leading_string(v))) return   ! several strings
      s = qs(unquote(v))
    end if
  end function as_single_quoted

  !> Characters in a quoted value; 0 if it is not a quoted string.
  pure integer function quoted_length(v)
    character(len=*), intent(in) :: v
    quoted_length = len(unquote(v))
  end function quoted_length

  !> A string as a namelist value: quoted, inner quotes doubled, trimmed.
  pure function qs(v) result(s)
    character(len=*), intent(in) :: v
    character(len=:), allocatable :: s
    integer :: i
    s = "'"
    do i = 1, len_trim(v)
      if (v(i:i) == "'") then
        s = s//"''"
      else
        s = s//v(i:i)
      end if
    end do
    s = s//"'"
  end function qs

  !> Shortest text that reads back to exactly x: plain decimal for moderate
  !> magnitudes, scientific otherwise.
  function r2s(x) result(s)
    real(rk), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=64) :: buf
    character(len=16) :: fmt
    real(rk) :: y
    integer :: d, ios, e

    if (.not. ieee_is_finite(x)) then
      write(buf, '(g0)') x
      s = trim(adjustl(buf))
      return
    end if
    if (x == 0) then
      s = '0.0'
      return
    end if
    if (abs(x) >= 1.0e-3_rk .and. abs(x) < 1.0e7_rk) then
      do d = 1, 25
        write(fmt, '(a,i0,a)') '(f0.', d, ')'
        write(buf, fmt) x
        read(buf, *, iostat=ios) y
        if (ios == 0 .and. y == x) exit
      end do
      s = trim(adjustl(buf))
      if (s(1:1) == '.') s = '0'//s
      if (s(1:2) == '-.') s = '-0'//s(2:)
    else
      do d = 0, 17
        write(fmt, '(a,i0,a)') '(es30.', d, 'e3)'
        write(buf, fmt) x
        read(buf, *, iostat=ios) y
        if (ios == 0 .and. y == x) exit
      end do
      buf = adjustl(buf)
      e = scan(buf, 'Ee')
      s = buf(1:e-1)
      if (index(s, '.') == 0) s = s//'.0'
      if (s(len(s):len(s)) == '.') s = s//'0'
      read(buf(e+1:), *) d
      s = s//'e'//itoa(d)
    end if
  end function r2s

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

  pure function itoa(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=16) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function itoa

  pure function ltoa(l) result(s)
    logical, intent(in) :: l
    character(len=:), allocatable :: s
    if (l) then
      s = '.true.'
    else
      s = '.false.'
    end if
  end function ltoa

  !> Cut long values for messages (to 60 characters unless told).
  pure function shorten(s, n) result(r)
    character(len=*), intent(in) :: s
    integer, intent(in), optional :: n
    character(len=:), allocatable :: r
    integer :: m
    m = 60
    if (present(n)) m = max(n, 4)
    if (len(s) > m) then
      r = s(1:m-3)//'...'
    else
      r = s
    end if
  end function shorten

  !> Folder part of a path, with its trailing '/'; '' for a bare file name.
  pure function dir_of(path) result(d)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: d
    d = path(1:index(path, '/', back=.true.))
  end function dir_of

  !> File name without folder and extension: 'decks/impact.nml' -> 'impact'.
  pure function stem_of(path) result(s)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: s
    integer :: k
    s = path(index(path, '/', back=.true.) + 1:)
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
