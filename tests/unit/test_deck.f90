!> Unit test of the input deck reader (udar_deck, udar_nml_scan, udar_input_errors).
!>
!> Usage: test_deck [DECK_DIR [WORK]]
!>   DECK_DIR  folder with the test decks, or its parent (tests/unit, as
!>             tests/run_tests.sh passes it); default tests/unit/decks
!>   WORK      scratch place for the resolved deck of the round trip: a folder
!>             if it exists, else a file name prefix; default: current folder
!>
!> One valid deck: values, derived values and the round trip of its resolved
!> text. One bad deck per class of mistake: the expected message (file, line,
!> group, variable) and, where the deck has a single mistake, no more than one
!> message (no follow-on noise).
module test_deck_support
  use udar_kinds, only: rk
  use udar_config
  use udar_deck, only: deck_read, deck_write_resolved, deck_where
  use udar_input_errors, only: input_errors_t, input_errors_report
  use udar_strings, only: itoa
  implicit none
  private
  public :: run_all

  character(len=*), parameter :: nl = achar(10)
  character(len=:), allocatable :: dir, scratch
  integer :: nfail = 0

  !> A deck with one mistake (see expect_one): the test name, the deck, how
  !> many messages it gives, and fragments of the expected message.
  type :: bad_deck_t
    character(len=24) :: name
    character(len=28) :: file
    integer :: n_expected
    character(len=32) :: frag_line
    character(len=48) :: frag2, frag3
  end type

  type(bad_deck_t), parameter :: bad_decks(*) = [ &
       bad_deck_t('unknown_variable', 'bad_unknown_variable.nml', 1, ':7:', "unknown variable 'youngs_modulos' in &material", "did you mean 'youngs_modulus'?"), &
       bad_deck_t('bad_value', 'bad_value.nml', 1, ':6:', "&material #1 'copper': rho0 = 8.9x3", 'not a valid real number'), &
       bad_deck_t('misspelled_group', 'bad_group_name.nml', 2, ':4:', 'unknown group &materail', '(did you mean &material?)'), &
       bad_deck_t('missing_slash', 'bad_missing_slash.nml', 1, ':2:', '&run (line 2)', "no closing '/'"), &
       bad_deck_t('missing_required_group', 'bad_missing_group.nml', 1, ': missing required group &part', '', ''), &
       bad_deck_t('missing_mesh_file', 'bad_mesh_file.nml', 1, ':4:', "&mesh: file = 'no_such_mesh.msh'", 'not found'), &
       bad_deck_t('unknown_part_material', 'bad_part_material.nml', 1, ':8:', "&part #1 'sphere': material = 'brass'", "(defined: 'copper', 'steel')"), &
       bad_deck_t('negative_density', 'bad_negative_density.nml', 1, ':5:', "&material #1 'copper': rho0 = -8930", 'must be > 0'), &
       bad_deck_t('poisson_out_of_range', 'bad_poisson.nml', 1, ':7:', 'poisson_ratio = 0.5', 'must be in (-1, 0.5)'), &
       bad_deck_t('t_end_not_positive', 'bad_t_end.nml', 1, ':4:', '&run: t_end = 0', 'must be > 0'), &
       bad_deck_t('bad_string_choice', 'bad_eos_choice.nml', 1, ':6:', "eos = 'mie'", "valid: 'linear', 'mie_gruneisen'"), &
       bad_deck_t('fracture_without_eps_f', 'bad_fracture_no_eps_f.nml', 1, ':4:', "&material #1 'copper': eps_f is required", "give > 0 for fracture = 'plastic_strain'"), &
       bad_deck_t('erosion_no_criterion', 'bad_erode_no_criterion.nml', 1, ":7: &material #1 'copper'", 'eps_erode = 1.5 : erosion needs a fracture', 'criterion: set fracture or p_spall'), &
       bad_deck_t('unknown_fracture_choice', 'bad_fracture_choice.nml', 1, ':7:', "&material #1 'copper': fracture = 'johnson-cook'", "'johnson_cook' (did you mean 'johnson_cook'?)") ]

contains

  !> Run every test; returns the number of failures.
  subroutine run_all(deck_dir, scratch_file, failures)
    character(len=*), intent(in) :: deck_dir, scratch_file
    integer, intent(out) :: failures
    integer :: k

    dir = deck_dir
    if (dir(len(dir):len(dir)) /= '/') dir = dir//'/'
    scratch = scratch_file
    nfail = 0

    call test_valid()
    call test_report_format()
    call test_missing_deck()
    do k = 1, size(bad_decks)
      call expect_one(trim(bad_decks(k)%name), trim(bad_decks(k)%file), bad_decks(k)%n_expected, &
                      trim(bad_decks(k)%frag_line), trim(bad_decks(k)%frag2), trim(bad_decks(k)%frag3))
    end do
    call test_several()
    call test_contact_errors()
    call test_no_contact()
    call test_fracture_jc()
    call test_fracture_plastic()
    call test_fracture_errors()
    call test_strength_models()
    call test_strength_model_errors()
    call test_include()

    failures = nfail
  end subroutine run_all

  subroutine pass(name)
    character(len=*), intent(in) :: name
    write(*, '(a)') 'PASS '//name
  end subroutine pass

  subroutine fail(name, detail)
    character(len=*), intent(in) :: name, detail
    write(*, '(a)') 'FAIL '//name//': '//detail
    nfail = nfail + 1
  end subroutine fail

  subroutine dump(errs)
    type(input_errors_t), intent(in) :: errs
    integer :: i
    do i = 1, errs%count()
      write(*, '(a)') '    | '//errs%message(i)
    end do
  end subroutine dump

  !> A deck with one mistake: exactly n_expected messages, one of which holds
  !> the file name with the line (frag_line, e.g. ':7:') and the other fragments.
  subroutine expect_one(name, file, n_expected, frag_line, frag2, frag3)
    character(len=*), intent(in) :: name, file, frag_line, frag2, frag3
    integer, intent(in) :: n_expected
    type(config_t) :: cfg
    type(input_errors_t) :: errs

    call deck_read(dir//file, cfg, errs)
    if (.not. errs%contains_text(file//frag_line, frag2, frag3)) then
      call fail(name, 'no message containing "'//file//frag_line//'" "'//frag2//'" "'//frag3//'"')
      call dump(errs)
    else if (errs%count() /= n_expected) then
      call fail(name, 'expected '//itoa(n_expected)//' message(s), got '//itoa(errs%count()))
      call dump(errs)
    else if (allocated(cfg%resolved_text)) then
      call fail(name, 'resolved_text set although the deck has errors')
    else
      call pass(name)
    end if
  end subroutine expect_one

  !> All mistakes of one deck are reported in one call, each at its line.
  subroutine test_several()
    character(len=*), parameter :: f = 'bad_several.nml'
    type(config_t) :: cfg
    type(input_errors_t) :: errs
    integer :: before

    call deck_read(dir//f, cfg, errs)
    before = nfail
    call has(f//':3:', '&run: t_end = -1e-5', 'must be > 0')
    call has(f//':4:', 'dt_safety = 1.5', 'in (0, 1]')
    call has(f//':5:', 'cycle_print = 10.5', 'not a valid integer')
    call has(f//':7:', "file = 'no_such_mesh.msh'", 'not found')
    call has(f//':8:', 'yield_stress', "strength = 'perfectly_plastic'")
    call has(f//':10:', 'rho0 = 8.9e3.x', 'not a valid real number')
    call has(f//':11:', "eos = 'mie'", 'unknown choice')
    call has(f//':12:', "'youngs_modulos'", "'youngs_modulus'")
    call has(f//':16:', 'unknown group &materail', '&material')
    call has(f//':17:', "material = 'brass'", "(defined: 'copper')")
    call has(f//':18:', "&boundary #1 'fixed'", 'surface')
    call has(f//':19:', "&boundary #2 'rigid_wall'", 'normal = 0, 0, 0')
    call has(f//':20:', '&output: dt_field = -1', 'must be >= 0')
    call has(f//':21:', '&output appears again', 'first at line 20')
    call has(f//':22:', '&run appears again', 'first at line 2')
    call has(f//':23:', "text outside any group: 'stray text'", '')
    ! the variable is named, and the '/' lost in the string is not reported again
    call has(f//':24:', "&numerics: q_linear = 'x", "unterminated string: add the closing '")
    if (errs%contains_text(f//':24:', '&numerics (line 24)', "no closing '/'")) &
         call fail('several_errors', "an unterminated string also reported as a missing '/'")
    if (nfail == before .and. errs%count() /= 17) &
         call fail('several_errors', 'expected 17 messages, got '//itoa(errs%count()))
    if (nfail == before) then
      call pass('several_errors')
    else
      call dump(errs)
    end if

  contains

    subroutine has(a, b, c)
      character(len=*), intent(in) :: a, b, c
      if (.not. errs%contains_text(a, b, c)) &
           call fail('several_errors', 'no message containing "'//a//'" "'//b//'" "'//c//'"')
    end subroutine has

  end subroutine test_several

  !> The mistakes of &contact groups, each named at its line: required names,
  !> self-contact, choice words, ranges.
  subroutine test_contact_errors()
    character(len=*), parameter :: f = 'bad_contact.nml'
    type(config_t) :: cfg
    type(input_errors_t) :: errs
    integer :: before

    call deck_read(dir//f, cfg, errs)
    before = nfail
    call has(f//":7: &contact #1 'plate': slave is required", 'physical surface group')
    call has(f//":8: &contact #2 'plate': weights = 'nearest'", "unknown choice; valid: 'distance', 'area'")
    call has(f//":9: &contact #3 'plate': friction = -1", 'must be >= 0')
    call has(f//":10: &contact #4 'sphere': symmetric = .true.", 'has no meaning for self-contact')
    call has(f//":11: &contact #5 'plate': master is required", 'a part')
    call has(f//':11:', 'iterations = 0', 'must be >= 1')
    call has(f//':11:', "initial_overlap = 'ignore'", "unknown choice; valid: 'report', 'move'")
    call has(f//":12: &contact #6 'plate': tolerance = -0.1", 'must be >= 0 (m/s)')
    if (nfail == before .and. errs%count() /= 8) &
         call fail('contact_errors', 'expected 8 messages, got '//itoa(errs%count()))
    if (nfail == before .and. allocated(cfg%resolved_text)) &
         call fail('contact_errors', 'resolved_text set although the deck has errors')
    if (nfail == before) then
      call pass('contact_errors')
    else
      call dump(errs)
    end if

  contains

    subroutine has(a, b, c)
      character(len=*), intent(in) :: a, b
      character(len=*), intent(in), optional :: c
      character(len=:), allocatable :: c_
      c_ = ''
      if (present(c)) c_ = c
      if (.not. errs%contains_text(a, b, c_)) &
           call fail('contact_errors', 'no message containing "'//a//'" "'//b//'" "'//c_//'"')
    end subroutine has

  end subroutine test_contact_errors

  !> A deck without &contact: no contacts (an allocated array of size 0), none
  !> in the resolved deck.
  subroutine test_no_contact()
    type(config_t) :: cfg
    type(input_errors_t) :: errs

    call deck_read(dir//'no_contact.nml', cfg, errs)
    if (errs%count() /= 0) then
      call fail('no_contact', 'unexpected errors')
      call dump(errs)
    else if (.not. allocated(cfg%contacts)) then
      call fail('no_contact', 'cfg%contacts not allocated')
    else if (size(cfg%contacts) /= 0) then
      call fail('no_contact', 'size(cfg%contacts) = '//itoa(size(cfg%contacts)))
    else if (index(cfg%resolved_text, '&contact') > 0) then
      call fail('no_contact', '&contact in the resolved deck')
    else
      call pass('no_contact')
    end if
  end subroutine test_no_contact

  subroutine test_missing_deck()
    type(config_t) :: cfg
    type(input_errors_t) :: errs
    call deck_read(dir//'no_such_deck.nml', cfg, errs)
    if (errs%count() == 1 .and. errs%contains_text('no_such_deck.nml', 'cannot read')) then
      call pass('missing_deck_file')
    else
      call fail('missing_deck_file', 'expected one "cannot read" message')
      call dump(errs)
    end if
  end subroutine test_missing_deck

  !> input_errors_report: every message, then one count line.
  subroutine test_report_format()
    type(input_errors_t) :: errs
    character(len=200) :: line
    integer :: u, n, ios
    call errs%add('a.nml:1: first')
    call errs%add('  a.nml:2: second  ')
    open(newunit=u, status='scratch', action='readwrite')
    call input_errors_report(errs, u)
    rewind(u)
    n = 0
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      n = n + 1
      if (n == 2 .and. line /= 'a.nml:2: second') n = -100
      if (n == 3 .and. line /= '2 input errors.') n = -100
    end do
    close(u)
    if (n == 3 .and. errs%message(2) == 'a.nml:2: second') then
      call pass('error_report_format')
    else
      call fail('error_report_format', 'unexpected report text')
    end if
  end subroutine test_report_format

  !> The valid deck: no errors, the values as written, the derived ones filled
  !> in, and the resolved deck reading back to the same configuration.
  subroutine test_valid()
    type(config_t) :: cfg
    type(input_errors_t) :: errs
    character(len=:), allocatable :: text, where
    integer :: before

    call deck_read(dir//'valid.nml', cfg, errs)
    if (errs%count() /= 0) then
      call fail('valid_deck', 'unexpected errors')
      call dump(errs)
      return
    end if
    before = nfail
    call check(cfg%run%title == 'Cu sphere / "steel" plate & co, t = 20 us ! not a comment', 'title')
    call check(cfg%run%t_end == 20e-6_rk, 't_end')
    call check(cfg%run%dt_safety == 0.6_rk .and. cfg%run%cycle_print == 50, 'run values')
    call check(cfg%mesh%file(1:1) == '/' .and. &
               index(cfg%mesh%file, '/tiny.msh', back=.true.) == len_trim(cfg%mesh%file) - 8, &
               'mesh file made absolute')
    call check(cfg%mesh%scale == 0.001_rk, 'scale')
    call check(size(cfg%materials) == 2 .and. size(cfg%parts) == 2 .and. &
               size(cfg%boundaries) == 3, 'group counts')
    associate(cu => cfg%materials(1), st => cfg%materials(2))
      call check(cu%name == 'copper' .and. cu%eos == eos_mie_gruneisen .and. &
                 cu%strength == strength_johnson_cook, 'copper models')
      call check(cu%bulk_modulus == 8930.0_rk * 3940.0_rk**2, 'copper K = rho0 c0^2')
      call check(cu%shear_modulus == 124e9_rk / (2 * 1.34_rk), 'copper G from E, nu')
      call check(cu%jc_n == 0.31_rk .and. cu%t_melt == 1356.0_rk, 'copper JC values')
      call check(cu%jc_rate_form == jc_rate_plastic, 'copper JC plastic-rate form')
      call check(cu%fracture == fracture_none .and. cu%eps_f == -1 .and. cu%jc_d1 == 0 .and. &
                 cu%jc_d5 == 0 .and. cu%p_spall == 0 .and. cu%eps_erode == 0, 'fracture defaults')
      call check(st%name == 'Steel' .and. st%eos == eos_linear .and. &
                 st%strength == strength_perfectly_plastic, 'steel models')
      call check(st%bulk_modulus == 166.7e9_rk .and. st%shear_modulus == 76.9e9_rk, 'steel K, G')
    end associate
    call check(cfg%parts(1)%group == 'sphere' .and. cfg%parts(1)%material == 'copper', 'part 1')
    call check(all(cfg%parts(1)%velocity == [0.0_rk, 0.0_rk, -227.0_rk]), 'velocity over lines')
    call check(cfg%parts(2)%material == 'Steel', 'material name in the material''s spelling')
    call check(cfg%boundaries(1)%kind == bc_rigid_wall .and. &
               cfg%boundaries(1)%wall_type == wall_sticking, 'rigid wall')
    call check(all(cfg%boundaries(1)%normal == [0.0_rk, 0.0_rk, 1.0_rk]), 'normal normalised')
    call check(cfg%boundaries(2)%kind == bc_symmetry .and. cfg%boundaries(2)%surface == 'x0', &
               'symmetry')
    call check(cfg%boundaries(3)%wall_type == wall_coulomb .and. cfg%boundaries(3)%friction == 0.2_rk, &
               'coulomb wall with friction')
    call check(size(cfg%contacts) == 2, 'number of contacts')
    if (size(cfg%contacts) == 2) then
      associate(c => cfg%contacts(1), d => cfg%contacts(2))
        call check(c%master == 'plate' .and. c%slave == 'sphere', 'contact 1 names')
        call check(c%friction == 0.18_rk .and. c%iterations == 3 .and. c%tolerance == 0.01_rk, &
                   'contact 1 numbers')
        call check(c%symmetric .and. c%weights == contact_weights_area .and. &
                   c%initial_overlap == overlap_move, 'contact 1 switches (choices case-insensitive)')
        call check(d%master == 'x0' .and. d%slave == 'sphere', 'contact 2 names')
        call check(d%friction == 0 .and. d%iterations == 50 .and. d%tolerance == 0 .and. &
                   .not. d%symmetric .and. d%weights == contact_weights_area .and. &
                   d%initial_overlap == overlap_report, 'contact 2 defaults')
      end associate
    end if
    call check(.not. cfg%numerics%anti_locking .and. cfg%numerics%q_linear == 0.1_rk, 'numerics')
    call check(cfg%numerics%erode_dt_ratio == 0.1_rk, 'erode_dt_ratio default')
    call check(cfg%output%directory == 'out/run 1' .and. cfg%output%case_name == 'valid', &
               'output, default case_name')
    call check(cfg%output%dt_checkpoint == 5e-6_rk .and. cfg%output%checkpoint_keep == 3, 'checkpoint values')
    call check(allocated(cfg%resolved_text), 'resolved_text set')
    if (nfail == before) call pass('valid_deck')

    ! the resolved deck marks defaults and derived values
    before = nfail
    call check(index(cfg%resolved_text, "dt_max = ") > 0, 'dt_max listed')
    call check(index(cfg%resolved_text, '(default)') > 0, '(default) markers')
    call check(index(cfg%resolved_text, '(derived: rho0*c0**2') > 0, '(derived) marker')
    ! Mie-Grueneisen with E and nu: the bulk modulus they imply is shown next to rho0*c0**2
    call check(index(cfg%resolved_text, 'imply E/(3(1-2nu)) = 1.2') > 0, 'implied bulk modulus shown')
    call check(index(cfg%resolved_text, nl//'&contact'//nl//"  master = 'plate'"//nl) > 0, &
               '&contact listed')
    call check(has_line("  tolerance = 0.01", '! m/s'), 'contact tolerance with its unit')
    call check(has_line("  weights = 'area'", '! distance | area'), 'contact weights with its choices')
    call check(has_line("  iterations = 50", '! - (default)'), 'contact iterations (default)')
    call check(has_line("  symmetric = .false.", '! (default)'), 'contact symmetric (default)')
    call check(has_line("  initial_overlap = 'report'", '! report | move (default)'), &
               'contact initial_overlap (default)')
    call check(has_line("  fracture = 'none'", '! none | plastic_strain | johnson_cook (default)'), &
               'fracture (default) with its choices')
    call check(has_line("  eps_f = -1.0", '! - (not set)'), 'eps_f (not set)')
    call check(has_line("  p_spall = 0.0", '! Pa (default)'), 'p_spall (default) with its unit')
    call check(has_line("  erode_dt_ratio = 0.1", '! - (default)'), 'erode_dt_ratio (default)')
    if (nfail == before) call pass('resolved_text_markers')

    ! round trip: the resolved deck reads back to the same configuration,
    ! also that of the public writer (default markers by value)
    call round_trip('round_trip', cfg, cfg%resolved_text)
    call deck_write_resolved(cfg, text)
    call round_trip('round_trip_public_writer', cfg, text)

    ! message prefixes for errors found later (mesh)
    where = deck_where(cfg, 'part', 2, 'group')
    if (index(where, "valid.nml:40: &part #2 'plate': group = 'plate'") > 0) then
      call pass('deck_where')
    else
      call fail('deck_where', 'got "'//where//'"')
    end if
    where = deck_where(cfg, 'contact', 2, 'slave')
    if (index(where, "valid.nml:59: &contact #2 'x0': slave = 'sphere'") > 0) then
      call pass('deck_where_contact')
    else
      call fail('deck_where_contact', 'got "'//where//'"')
    end if

  contains

    subroutine check(ok, what)
      logical, intent(in) :: ok
      character(len=*), intent(in) :: what
      if (.not. ok) call fail('valid_deck', what)
    end subroutine check

    logical function has_line(start, comment)
      character(len=*), intent(in) :: start, comment
      has_line = text_has_line(cfg%resolved_text, start, comment)
    end function has_line

  end subroutine test_valid

  !> The resolved deck text has a line that starts with start (the variable
  !> and its value) and ends with comment (unit and marker).
  logical function text_has_line(text, start, comment) result(has_line)
    character(len=*), intent(in) :: text, start, comment
    integer :: i, j
    has_line = .false.
    i = 1
    do while (i <= len(text))
      j = index(text(i:), nl)
      if (j == 0) j = len(text) - i + 2
      associate(line => text(i:i+j-2))
        if (index(line, start) == 1 .and. len(line) >= len(comment)) then
          if (line(len(line)-len(comment)+1:) == comment) has_line = .true.
        end if
      end associate
      i = i + j
    end do
  end function text_has_line

  !> The resolved deck text must read back to cfg (the scratch file is removed).
  subroutine round_trip(name, cfg, text)
    character(len=*), intent(in) :: name, text
    type(config_t), intent(in) :: cfg
    type(config_t) :: cfg2
    type(input_errors_t) :: errs2
    character(len=:), allocatable :: why
    integer :: u
    call write_file(scratch, text)
    call deck_read(scratch, cfg2, errs2)
    open(newunit=u, file=scratch, status='old')
    close(u, status='delete')
    if (errs2%count() /= 0) then
      call fail(name, 'the resolved deck does not read back:')
      call dump(errs2)
      write(*, '(a)') text
    else
      why = config_difference(cfg, cfg2)
      if (len(why) == 0) then
        call pass(name)
      else
        call fail(name, 'differs in '//why)
      end if
    end if
  end subroutine round_trip

  !> Johnson-Cook fracture with D1 .. D5, spall and erosion, and a fluid with a
  !> spall strength: the values as written, the resolved deck, its round trip.
  subroutine test_fracture_jc()
    type(config_t) :: cfg
    type(input_errors_t) :: errs
    integer :: before

    call deck_read(dir//'fracture_jc.nml', cfg, errs)
    if (errs%count() /= 0) then
      call fail('fracture_johnson_cook', 'unexpected errors')
      call dump(errs)
      return
    end if
    before = nfail
    call check(size(cfg%materials) == 2, 'number of materials')
    if (size(cfg%materials) == 2) then
      associate(st => cfg%materials(1), wa => cfg%materials(2))
        call check(st%fracture == fracture_johnson_cook, 'steel fracture = johnson_cook (case-insensitive)')
        call check(st%jc_d1 == 0.05_rk .and. st%jc_d2 == 3.44_rk .and. st%jc_d3 == -2.12_rk .and. &
                   st%jc_d4 == 0.002_rk .and. st%jc_d5 == 0.61_rk, 'steel D1 .. D5')
        call check(st%eps_f == -1, 'steel eps_f not set')
        call check(st%p_spall == 1.5e9_rk .and. st%eps_erode == 1.2_rk, 'steel p_spall, eps_erode')
        call check(wa%strength == strength_none .and. wa%fracture == fracture_none, 'water models')
        call check(wa%p_spall == 1e6_rk .and. wa%eps_erode == 2.0_rk, 'water p_spall, eps_erode')
      end associate
    end if
    call check(cfg%numerics%erode_dt_ratio == 0.05_rk, 'erode_dt_ratio')
    call check(text_has_line(cfg%resolved_text, "  fracture = 'johnson_cook'", &
               '! none | plastic_strain | johnson_cook'), 'resolved fracture with its choices')
    call check(text_has_line(cfg%resolved_text, "  jc_d3 = -2.12", '! -'), 'resolved jc_d3')
    call check(text_has_line(cfg%resolved_text, "  p_spall = 1.5e9", '! Pa'), 'resolved p_spall')
    call check(text_has_line(cfg%resolved_text, "  erode_dt_ratio = 0.05", '! -'), 'resolved erode_dt_ratio')
    if (nfail == before) then
      call pass('fracture_johnson_cook')
    else
      write(*, '(a)') cfg%resolved_text
    end if
    call round_trip('fracture_johnson_cook_round_trip', cfg, cfg%resolved_text)

  contains

    subroutine check(ok, what)
      logical, intent(in) :: ok
      character(len=*), intent(in) :: what
      if (.not. ok) call fail('fracture_johnson_cook', what)
    end subroutine check

  end subroutine test_fracture_jc

  !> Plastic-strain fracture with eps_f; Johnson-Cook fracture with a
  !> non-Johnson-Cook strength, which may set the reference rate jc_rate0.
  subroutine test_fracture_plastic()
    type(config_t) :: cfg
    type(input_errors_t) :: errs
    integer :: before

    call deck_read(dir//'fracture_plastic.nml', cfg, errs)
    if (errs%count() /= 0) then
      call fail('fracture_plastic_strain', 'unexpected errors')
      call dump(errs)
      return
    end if
    before = nfail
    associate(al => cfg%materials(1), st => cfg%materials(2))
      call check(al%fracture == fracture_plastic_strain .and. al%eps_f == 0.8_rk, 'aluminium eps_f')
      call check(al%jc_d1 == 0 .and. al%jc_d2 == 0 .and. al%p_spall == 0 .and. al%eps_erode == 0, &
                 'aluminium defaults')
      call check(st%fracture == fracture_johnson_cook .and. st%strength == strength_linear_hardening, &
                 'steel models')
      call check(st%jc_d1 == 0.05_rk .and. st%jc_d2 == 3.44_rk .and. st%jc_d3 == -2.12_rk .and. &
                 st%jc_d4 == 0 .and. st%jc_d5 == 0, 'steel D1 .. D5')
      call check(st%jc_rate0 == 0.1_rk, 'steel jc_rate0 for fracture')
    end associate
    call check(cfg%numerics%erode_dt_ratio == 0.1_rk, 'erode_dt_ratio default')
    if (nfail == before) call pass('fracture_plastic_strain')
    call round_trip('fracture_plastic_strain_round_trip', cfg, cfg%resolved_text)

  contains

    subroutine check(ok, what)
      logical, intent(in) :: ok
      character(len=*), intent(in) :: what
      if (.not. ok) call fail('fracture_plastic_strain', what)
    end subroutine check

  end subroutine test_fracture_plastic

  !> The other mistakes of fracture and erosion, each named at its line.
  subroutine test_fracture_errors()
    character(len=*), parameter :: f = 'bad_fracture.nml'
    type(config_t) :: cfg
    type(input_errors_t) :: errs
    integer :: before

    call deck_read(dir//f, cfg, errs)
    before = nfail
    call has(f//":5: &material #1 'a': jc_d2 = -0.5 : jc_d1 + jc_d2 = 0", &
             "must be > 0 for fracture = 'johnson_cook'")
    call has(f//":6: &material #2 'b': jc_d1 and jc_d2 are required but not set", &
             "give jc_d1 + jc_d2 > 0 for fracture = 'johnson_cook'")
    call has(f//":8: &material #3 'c': t_melt is required but not set", &
             "> t_room = 294", "with jc_d5 /= 0")
    call has(f//":10: &material #3 'c': eps_f = 0.5 : set, but fracture = 'johnson_cook'", &
             'computes the fracture strain from jc_d1 .. jc_d5')
    call has(f//":12: &material #4 'd': eps_f = 0.5 : set, but only used with", &
             "fracture = 'plastic_strain'")
    call has(f//":12: &material #4 'd': jc_d3 = -1.5 : set, but only used with", &
             "fracture = 'johnson_cook'")
    call has(f//":12: &material #4 'd': p_spall = -1e9 : must be >= 0 (Pa)", '')
    call has(f//":12: &material #4 'd': eps_erode = -1 : must be >= 0", '')
    call has(f//":14: &material #5 'e': eps_f = 0 : must be > 0 for fracture = 'plastic_strain'", '')
    call has(f//":14: &material #5 'e': jc_d1 = 0.1 : set, but only used with", "fracture = 'johnson_cook'")
    call has(f//':16: &numerics: erode_dt_ratio = 1.0 : must be in [0, 1)', '')
    if (nfail == before .and. errs%count() /= 11) &
         call fail('fracture_errors', 'expected 11 messages, got '//itoa(errs%count()))
    if (nfail == before .and. allocated(cfg%resolved_text)) &
         call fail('fracture_errors', 'resolved_text set although the deck has errors')
    if (nfail == before) then
      call pass('fracture_errors')
    else
      call dump(errs)
    end if

  contains

    subroutine has(a, b, c)
      character(len=*), intent(in) :: a, b
      character(len=*), intent(in), optional :: c
      character(len=:), allocatable :: c_
      c_ = ''
      if (present(c)) c_ = c
      if (.not. errs%contains_text(a, b, c_)) &
           call fail('fracture_errors', 'no message containing "'//a//'" "'//b//'" "'//c_//'"')
    end subroutine has

  end subroutine test_fracture_errors

  !> Zerilli-Armstrong and Steinberg-Guinan with the shear modulus and melt
  !> models, a part at its own temperature: the values, the resolved deck
  !> and its round trip.
  subroutine test_strength_models()
    type(config_t) :: cfg
    type(input_errors_t) :: errs
    integer :: before

    call deck_read(dir//'strength_models.nml', cfg, errs)
    if (errs%count() /= 0) then
      call fail('strength_models', 'unexpected errors')
      call dump(errs)
      return
    end if
    before = nfail
    associate(cu => cfg%materials(1), w => cfg%materials(2))
      call check(cu%strength == strength_zerilli_armstrong .and. cu%za_c2 == 890e6_rk .and. &
                 cu%za_c4 == 0.000115_rk .and. cu%za_n == 1 .and. cu%za_rate0 == 1, 'copper ZA constants')
      call check(cu%shear_model == shear_constant .and. cu%melt_model == melt_constant, 'copper default models')
      call check(w%strength == strength_steinberg_guinan .and. w%sg_ymax == 4.0e9_rk .and. w%sg_n == 0.13_rk, &
                 'tungsten SCG constants')
      call check(w%shear_model == shear_steinberg_guinan .and. w%sg_a == 1.03e-11_rk .and. w%sg_t0 == 300, &
                 'tungsten shear model (case-insensitive), default t0')
      call check(w%melt_model == melt_steinberg_guinan .and. w%melt_a == 1.3_rk, 'tungsten melt model')
    end associate
    call check(cfg%parts(1)%initial_temperature == 720, 'part 1 at 720 K')
    call check(cfg%parts(2)%initial_temperature == 294, "part 2 at its material's (t_room)")
    call check(text_has_line(cfg%resolved_text, "  shear_model = 'steinberg_guinan'", &
               '! constant | steinberg_guinan | mts | ptw'), 'resolved shear_model with its choices')
    call check(text_has_line(cfg%resolved_text, "  sg_a = 1.03e-11", '! 1/Pa'), 'resolved sg_a')
    if (nfail == before) then
      call pass('strength_models')
    else
      write(*, '(a)') cfg%resolved_text
    end if
    call round_trip('strength_models_round_trip', cfg, cfg%resolved_text)

  contains

    subroutine check(ok, what)
      logical, intent(in) :: ok
      character(len=*), intent(in) :: what
      if (.not. ok) call fail('strength_models', what)
    end subroutine check

  end subroutine test_strength_models

  !> The mistakes of the models of issue 16, one or two per material.
  subroutine test_strength_model_errors()
    character(len=*), parameter :: f = 'bad_strength_models.nml'
    type(config_t) :: cfg
    type(input_errors_t) :: errs
    integer :: before

    call deck_read(dir//f, cfg, errs)
    before = nfail
    call has(f//":4: &material #1 'a': za_c0, za_c1, za_c2 and za_c5 are all 0", 'needs a flow stress')
    call has(f//":4: &material #1 'a': specific_heat is required but not set", &
             "strength = 'zerilli_armstrong' (the temperature")
    call has(f//":7: &material #2 'b': sg_ymax = 0.1e9 : must be >= sg_y0", '')
    call has(f//":10: &material #3 'c': shear_model = 'steinberg_guinan' : 'steinberg_guinan' serves", &
             "the other models take shear_modulus")
    call has(f//":11: &material #4 'd': t_melt is required but not set", "melt_model = 'steinberg_guinan'")
    call has(f//":13: &material #4 'd': melt_model = 'steinberg_guinan' :", "takes gamma0 of eos = 'mie_gruneisen'")
    call has(f//":13: &material #4 'd': za_c2 = 890e6 : set, but only used with", "strength = 'zerilli_armstrong'")
    call has(f//":14: &part #1 'sphere': initial_temperature = -5 : must be > 0 (K)", '')
    call has(f//":15: &material #5 'e': mts_kb3 is required but not set", "strength = 'mts' (Boltzmann")
    call has(f//":15: &material #5 'e': mts_sigma0es is required but not set", 'saturation threshold stress')
    call has(f//":15: &material #5 'e': specific_heat is required but not set", "strength = 'mts'")
    call has(f//":15: &material #5 'e': mts_t0 is required but not set", "shear_model = 'mts'")
    call has(f//":17: &material #6 'f': ptw_molar_mass is required but not set", "strength = 'ptw' (kg/mol")
    call has(f//":17: &material #6 'f': t_melt is required but not set", "strength = 'ptw' (its homologous")
    call has(f//":7: &material #2 'b': sl_c1 = 1e6 : set, but only used with", "strength = 'steinberg_lund'")
    call has(f//":19: &material #7 'g': sl_uk is required but not set", "(the kink-pair energy in J")
    call has(f//":19: &material #7 'g': sl_c1 is required but not set", "strength = 'steinberg_lund'")
    call has(f//":20: &material #7 'g': sl_c2 = -1 : must be >= 0", '')
    call has(f//":21: &material #8 'h': specific_heat is required but not set", "for shock_heating (the temperature")
    if (nfail == before .and. errs%count() /= 19) &
         call fail('strength_model_errors', 'expected 19 messages, got '//itoa(errs%count()))
    if (nfail == before) then
      call pass('strength_model_errors')
    else
      call dump(errs)
    end if

  contains

    subroutine has(a, b, c)
      character(len=*), intent(in) :: a, b
      character(len=*), intent(in), optional :: c
      character(len=:), allocatable :: c_
      c_ = ''
      if (present(c)) c_ = c
      if (.not. errs%contains_text(a, b, c_)) &
           call fail('strength_model_errors', 'no message containing "'//a//'" "'//b//'" "'//c_//'"')
    end subroutine has

  end subroutine test_strength_model_errors

  !> A deck that includes library files: the materials are there; an include
  !> that cannot be read, and a mistake inside an included file, are
  !> reported at their own file and line.
  subroutine test_include()
    type(config_t) :: cfg
    type(input_errors_t) :: errs
    call deck_read(dir//'include_library.nml', cfg, errs)
    if (errs%count() /= 0) then
      call fail('include_library', 'unexpected errors')
      call dump(errs)
    else if (size(cfg%materials) /= 2) then
      call fail('include_library', 'expected the two included materials')
    else if (cfg%materials(1)%za_c2 /= 890e6_rk .or. cfg%materials(2)%jc_b /= 292e6_rk .or. &
             cfg%parts(2)%material /= 'ofhc_copper_jc') then
      call fail('include_library', 'the included values')
    else
      call pass('include_library')
    end if
    call deck_read(dir//'bad_include.nml', cfg, errs)
    if (.not. errs%contains_text("bad_include.nml:3: include 'no_such_library.nml': cannot read", &
                                 "taken from the including file's folder", '')) then
      call fail('include_errors', 'no message for the missing include')
      call dump(errs)
    else if (.not. errs%contains_text("decks/bad_library.nml:4: &material #1 'x': rho0 = -1 : must be > 0", '', '')) then
      call fail('include_errors', 'no message at the included file and line')
      call dump(errs)
    else if (errs%count() /= 2) then
      call fail('include_errors', 'expected 2 messages')
      call dump(errs)
    else
      call pass('include_errors')
    end if
  end subroutine test_include

  subroutine write_file(path, text)
    character(len=*), intent(in) :: path, text
    integer :: u
    open(newunit=u, file=path, access='stream', form='unformatted', status='replace', action='write')
    write(u) text
    close(u)
  end subroutine write_file

  !> '' if a and b agree in every deck value, else a difference.
  function config_difference(a, b) result(why)
    type(config_t), intent(in) :: a, b
    character(len=:), allocatable :: why
    integer :: k
    ! the numbers of instances first: the instances are compared one by one
    why = ''
    if (size(a%materials) /= size(b%materials)) then
      why = 'number of materials'
    else if (size(a%parts) /= size(b%parts)) then
      why = 'number of parts'
    else if (size(a%boundaries) /= size(b%boundaries)) then
      why = 'number of boundaries'
    else if (size(a%contacts) /= size(b%contacts)) then
      why = 'number of contacts'
    end if
    if (len(why) > 0) return
    associate(r => a%run, s => b%run)
      if (r%title /= s%title) why = 'run%title'
      if (r%t_end /= s%t_end) why = 'run%t_end'
      if (r%dt_safety /= s%dt_safety) why = 'run%dt_safety'
      if (r%dt_initial /= s%dt_initial) why = 'run%dt_initial'
      if (r%dt_max /= s%dt_max) why = 'run%dt_max'
      if (r%max_cycles /= s%max_cycles) why = 'run%max_cycles'
      if (r%cycle_print /= s%cycle_print) why = 'run%cycle_print'
      if (r%energy_error_limit /= s%energy_error_limit) why = 'run%energy_error_limit'
      if (r%wall_limit /= s%wall_limit) why = 'run%wall_limit'
    end associate
    if (a%mesh%file /= b%mesh%file) why = 'mesh%file'
    if (a%mesh%scale /= b%mesh%scale) why = 'mesh%scale'
    do k = 1, size(a%materials)
      associate(m => a%materials(k), n => b%materials(k))
        if (m%name /= n%name) why = 'material%name'
        if (m%rho0 /= n%rho0) why = 'material%rho0'
        if (m%eos /= n%eos) why = 'material%eos'
        if (m%bulk_modulus /= n%bulk_modulus) why = 'material%bulk_modulus'
        if (m%c0 /= n%c0) why = 'material%c0'
        if (m%s /= n%s) why = 'material%s'
        if (m%gamma0 /= n%gamma0) why = 'material%gamma0'
        if (m%strength /= n%strength) why = 'material%strength'
        if (m%shear_modulus /= n%shear_modulus) why = 'material%shear_modulus'
        if (m%youngs_modulus /= n%youngs_modulus) why = 'material%youngs_modulus'
        if (m%poisson_ratio /= n%poisson_ratio) why = 'material%poisson_ratio'
        if (m%yield_stress /= n%yield_stress) why = 'material%yield_stress'
        if (m%hardening_modulus /= n%hardening_modulus) why = 'material%hardening_modulus'
        if (m%jc_a /= n%jc_a) why = 'material%jc_a'
        if (m%jc_b /= n%jc_b) why = 'material%jc_b'
        if (m%jc_n /= n%jc_n) why = 'material%jc_n'
        if (m%jc_c /= n%jc_c) why = 'material%jc_c'
        if (m%jc_m /= n%jc_m) why = 'material%jc_m'
        if (m%jc_rate0 /= n%jc_rate0) why = 'material%jc_rate0'
        if (m%jc_rate_form /= n%jc_rate_form) why = 'material%jc_rate_form'
        if (m%t_melt /= n%t_melt) why = 'material%t_melt'
        if (m%t_room /= n%t_room) why = 'material%t_room'
        if (m%specific_heat /= n%specific_heat) why = 'material%specific_heat'
        if (m%taylor_quinney /= n%taylor_quinney) why = 'material%taylor_quinney'
        if (m%initial_temperature /= n%initial_temperature) why = 'material%initial_temperature'
        if (m%fracture /= n%fracture) why = 'material%fracture'
        if (m%eps_f /= n%eps_f) why = 'material%eps_f'
        if (m%jc_d1 /= n%jc_d1) why = 'material%jc_d1'
        if (m%jc_d2 /= n%jc_d2) why = 'material%jc_d2'
        if (m%jc_d3 /= n%jc_d3) why = 'material%jc_d3'
        if (m%jc_d4 /= n%jc_d4) why = 'material%jc_d4'
        if (m%jc_d5 /= n%jc_d5) why = 'material%jc_d5'
        if (m%p_spall /= n%p_spall) why = 'material%p_spall'
        if (m%eps_erode /= n%eps_erode) why = 'material%eps_erode'
        if (any([m%za_c0, m%za_c1, m%za_c2, m%za_c3, m%za_c4, m%za_c5, m%za_n, m%za_rate0] /= &
                [n%za_c0, n%za_c1, n%za_c2, n%za_c3, n%za_c4, n%za_c5, n%za_n, n%za_rate0])) why = 'material%za_*'
        if (any([m%sg_y0, m%sg_ymax, m%sg_beta, m%sg_n, m%sg_eps_i, m%sg_a, m%sg_b, m%sg_t0, m%melt_a] /= &
                [n%sg_y0, n%sg_ymax, n%sg_beta, n%sg_n, n%sg_eps_i, n%sg_a, n%sg_b, n%sg_t0, n%melt_a])) &
             why = 'material%sg_*, melt_a'
        if (m%shear_model /= n%shear_model) why = 'material%shear_model'
        if (any([m%mts_sigma_a, m%mts_sigma_i, m%mts_g0i, m%mts_rate0i, m%mts_pi, m%mts_qi, m%mts_g0e, &
                 m%mts_rate0e, m%mts_pe, m%mts_qe, m%mts_kb3, m%mts_a0, m%mts_a1, m%mts_a2, m%mts_a3, &
                 m%mts_theta_iv, m%mts_alpha, m%mts_sigma0es, m%mts_g0es, m%mts_rate0es, m%mts_d, m%mts_t0] /= &
                [n%mts_sigma_a, n%mts_sigma_i, n%mts_g0i, n%mts_rate0i, n%mts_pi, n%mts_qi, n%mts_g0e, &
                 n%mts_rate0e, n%mts_pe, n%mts_qe, n%mts_kb3, n%mts_a0, n%mts_a1, n%mts_a2, n%mts_a3, &
                 n%mts_theta_iv, n%mts_alpha, n%mts_sigma0es, n%mts_g0es, n%mts_rate0es, n%mts_d, n%mts_t0])) &
             why = 'material%mts_*'
        if (any([m%ptw_theta, m%ptw_p, m%ptw_s0, m%ptw_sinf, m%ptw_kappa, m%ptw_gamma, m%ptw_y0, m%ptw_yinf, &
                 m%ptw_y1, m%ptw_y2, m%ptw_beta, m%ptw_molar_mass, m%ptw_alpha] /= &
                [n%ptw_theta, n%ptw_p, n%ptw_s0, n%ptw_sinf, n%ptw_kappa, n%ptw_gamma, n%ptw_y0, n%ptw_yinf, &
                 n%ptw_y1, n%ptw_y2, n%ptw_beta, n%ptw_molar_mass, n%ptw_alpha])) why = 'material%ptw_*'
        if (m%melt_model /= n%melt_model) why = 'material%melt_model'
      end associate
    end do
    do k = 1, size(a%parts)
      if (a%parts(k)%group /= b%parts(k)%group) why = 'part%group'
      if (a%parts(k)%material /= b%parts(k)%material) why = 'part%material'
      if (any(a%parts(k)%velocity /= b%parts(k)%velocity)) why = 'part%velocity'
      if (a%parts(k)%initial_temperature /= b%parts(k)%initial_temperature) why = 'part%initial_temperature'
    end do
    do k = 1, size(a%boundaries)
      associate(p => a%boundaries(k), q => b%boundaries(k))
        if (p%kind /= q%kind) why = 'boundary%kind'
        if (p%surface /= q%surface) why = 'boundary%surface'
        if (any(p%point /= q%point)) why = 'boundary%point'
        if (any(p%normal /= q%normal)) why = 'boundary%normal'
        if (p%wall_type /= q%wall_type) why = 'boundary%wall_type'
        if (p%friction /= q%friction) why = 'boundary%friction'
      end associate
    end do
    do k = 1, size(a%contacts)
      associate(p => a%contacts(k), q => b%contacts(k))
        if (p%master /= q%master) why = 'contact%master'
        if (p%slave /= q%slave) why = 'contact%slave'
        if (p%friction /= q%friction) why = 'contact%friction'
        if (p%iterations /= q%iterations) why = 'contact%iterations'
        if (p%tolerance /= q%tolerance) why = 'contact%tolerance'
        if (p%symmetric .neqv. q%symmetric) why = 'contact%symmetric'
        if (p%weights /= q%weights) why = 'contact%weights'
        if (p%initial_overlap /= q%initial_overlap) why = 'contact%initial_overlap'
      end associate
    end do
    if (a%numerics%anti_locking .neqv. b%numerics%anti_locking) why = 'numerics%anti_locking'
    if (a%numerics%q_linear /= b%numerics%q_linear) why = 'numerics%q_linear'
    if (a%numerics%q_quadratic /= b%numerics%q_quadratic) why = 'numerics%q_quadratic'
    if (a%numerics%erode_dt_ratio /= b%numerics%erode_dt_ratio) why = 'numerics%erode_dt_ratio'
    if (a%output%directory /= b%output%directory) why = 'output%directory'
    if (a%output%case_name /= b%output%case_name) why = 'output%case_name'
    if (a%output%dt_field /= b%output%dt_field) why = 'output%dt_field'
    if (a%output%dt_history /= b%output%dt_history) why = 'output%dt_history'
    if (a%output%dt_checkpoint /= b%output%dt_checkpoint) why = 'output%dt_checkpoint'
    if (a%output%checkpoint_keep /= b%output%checkpoint_keep) why = 'output%checkpoint_keep'
  end function config_difference

end module test_deck_support

program test_deck
  use test_deck_support, only: run_all
  implicit none
  character(len=1024) :: arg
  character(len=:), allocatable :: deck_dir, scratch
  logical :: exists
  integer :: failures

  call get_command_argument(1, arg)
  if (len_trim(arg) == 0) arg = 'tests/unit/decks'
  deck_dir = trim(arg)
  inquire(file=deck_dir//'/decks/valid.nml', exist=exists)
  if (exists) deck_dir = deck_dir//'/decks'

  call get_command_argument(2, arg)
  if (len_trim(arg) == 0) then
    scratch = 'test_deck_resolved.nml'
  else
    inquire(file=trim(arg)//'/.', exist=exists)
    if (exists) then
      scratch = trim(arg)//'/resolved.nml'
    else
      scratch = trim(arg)//'_resolved.nml'
    end if
  end if

  call run_all(deck_dir, scratch, failures)
  if (failures > 0) then
    write(*, '(i0,a)') failures, ' test(s) FAILED'
    error stop 1
  end if
  write(*, '(a)') 'all deck tests passed'
end program test_deck
