!> udar: explicit Lagrangian FEM for high-velocity impact of deformable solids.
!> init -> run -> finalize.
program udar
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use udar_kinds, only: rk, max_path_len
  use udar_comms, only: comms_init, comms_finalize, comms_is_root, comms_size
  use udar_fatal, only: fatal, exit_input
  use udar_log, only: log_info, log_warn
  use udar_version, only: program_version
  use udar_config, only: config_t
  use udar_input_errors, only: input_errors_t, input_errors_report
  use udar_deck, only: deck_read
  use udar_gmsh, only: gmsh_mesh_t, gmsh_read
  use udar_domain, only: domain_t
  use udar_setup, only: build_domain, count_bodies
  use udar_run, only: run_simulation, run_result_t
  use udar_partition, only: partition_elements, partition_stats_t
  use udar_decomposition, only: rank_counts_t, decomposition_counts
  use udar_strings, only: itoa
  implicit none

  type(config_t) :: cfg
  type(input_errors_t) :: errs
  type(gmsh_mesh_t) :: mesh
  type(domain_t) :: dom
  type(run_result_t) :: res
  character(len=max_path_len) :: arg, deck_path
  logical :: check_only, ok
  character(len=:), allocatable :: msg
  character(len=512) :: line
  integer :: k, ios, n_bodies
  integer :: preview_ranks = 0    !< --ranks N: show the partition for N ranks (with --check)

  call comms_init()
  check_only = .false.
  deck_path = ''
  do k = 1, command_argument_count()
    call get_command_argument(k, arg)
    if (preview_ranks == -1) then     ! the value after --ranks
      read(arg, *, iostat=ios) preview_ranks
      if (ios /= 0 .or. preview_ranks < 1) call fatal(exit_input, '--ranks '//trim(arg)// &
                                                       ': expected a positive number of ranks')
      cycle
    end if
    select case (trim(arg))
    case ('--help', '-h')
      call usage()
      call comms_finalize(); stop
    case ('--version')
      call log_info('udar '//program_version)
      call comms_finalize(); stop
    case ('--check')
      check_only = .true.
    case ('--ranks')
      if (k == command_argument_count()) call fatal(exit_input, '--ranks needs a number of ranks')
      preview_ranks = -1
    case default
      if (arg(1:1) == '-') call fatal(exit_input, 'unknown option '//trim(arg)//' (see udar --help)')
      if (len_trim(deck_path) > 0) call fatal(exit_input, 'more than one deck given: '//trim(deck_path)// &
                                              ' and '//trim(arg))
      deck_path = arg
    end select
  end do
  if (preview_ranks > 0 .and. .not. check_only) call fatal(exit_input, '--ranks goes with --check '// &
    '(this version runs on one rank)')
  if (len_trim(deck_path) == 0) then
    call usage()
    call fatal(exit_input, 'no input deck given')
  end if

  ! ---- input: every mistake in the deck and its mesh reported at once
  call deck_read(trim(deck_path), cfg, errs)
  if (errs%count() == 0) then
    call gmsh_read(trim(cfg%mesh%file), cfg%mesh%scale, mesh, ok, msg)
    if (.not. ok) then
      call errs%add(trim(deck_path)//': &mesh file: '//msg)
    else
      call build_domain(cfg, mesh, dom, errs)
    end if
  end if
  if (errs%count() > 0) then
    if (comms_is_root()) call input_errors_report(errs, error_unit)
    call fatal(exit_input, 'input deck '//trim(deck_path)//' has errors; nothing was run or written')
  end if
  if (comms_size() > 1) call fatal(exit_input, 'this build runs on one MPI rank only '// &
                                   '(domain decomposition is not implemented yet)')
  write(line, '(a,i0,a,i0,a,i0,a)') 'mesh '//trim(cfg%mesh%file)//': ', mesh%n_nodes, ' nodes, ', mesh%n_tets, &
    ' tetrahedra, ', mesh%n_inverted, ' reoriented at read time'
  call log_info(line)
  n_bodies = count_bodies(dom)
  if (n_bodies > 1) then
    write(line, '(a,i0,a)') 'the mesh holds ', n_bodies, ' separate bodies; this version has no contact '// &
      'between bodies (next issues), so they will pass through each other'
    call log_warn(line)
  end if

  if (check_only) then
    if (comms_is_root()) write(output_unit, '(a)') cfg%resolved_text
    if (preview_ranks > 0) call report_partition(dom, preview_ranks)
    call log_info('deck '//trim(deck_path)//' is valid')
    call comms_finalize()
    stop
  end if

  if (cfg%run%wall_limit > 0.0_rk) call log_warn('&run wall_limit is not active yet: it needs checkpoint/restart '// &
                                                 '(to come with the domain-decomposition issue); the run ignores it')
  call log_info('udar '//program_version//': '//trim(cfg%run%title))
  call run_simulation(cfg, dom, res)
  write(line, '(a,i0,a,es12.5,a,es10.3,a,f0.2,a,f0.1,a)') 'udar: done: ', res%cycles, ' cycles to t = ', &
    res%time, ' s, energy error ', res%energy_error, ', ', res%wall_seconds, ' s wall (', &
    res%ns_per_element_cycle, ' ns per element-cycle); fields '// &
    trim(res%field_file)//', history '//trim(res%history_file)
  call log_info(line)
  call comms_finalize()

contains

  !> The METIS partition of the elements over n ranks and what each rank
  !> would own and hold as ghosts.
  subroutine report_partition(dom, n)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: n
    integer, allocatable :: part(:)
    type(partition_stats_t) :: stats
    type(rank_counts_t), allocatable :: counts(:)
    integer :: r
    allocate(part(dom%n_elems), counts(0:n-1))
    call partition_elements(dom%n_nodes, dom%el_conn, n, part, stats, ok, msg)
    if (.not. ok) call fatal(exit_input, 'partition for '//itoa(n)//' ranks: '//msg)
    call decomposition_counts(dom%el_conn, dom%nd_el_ptr, dom%nd_el, part, n, counts)
    write(line, '(a,i0,a,i0,a,f6.3)') 'partition for ', n, ' ranks (METIS k-way, element dual graph): edge cut ', &
      stats%edge_cut, ' faces, load imbalance ', stats%imbalance
    call log_info(line)
    call log_info('  rank  owned_elems  owned_nodes  ghost_elems  ghost_nodes')
    do r = 0, n - 1
      write(line, '(i6,4i13)') r, counts(r)%owned_elems, counts(r)%owned_nodes, counts(r)%ghost_elems, &
        counts(r)%ghost_nodes
      call log_info(line)
    end do
  end subroutine

  subroutine usage()
    call log_info('usage: udar [--check [--ranks N]] DECK.nml | --help | --version')
    call log_info('  DECK.nml     run the namelist input deck')
    call log_info('  --check      validate the deck and its mesh, print the resolved deck, run nothing')
    call log_info('  --ranks N    with --check: show how the mesh would be split over N MPI ranks')
    call log_info('  --help       this text;  --version  the program version')
    call log_info('Exit codes: 0 done, 1 input error, 2 the run went bad (physics), 3 I/O error.')
  end subroutine
end program udar
