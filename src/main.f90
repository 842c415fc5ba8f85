!> udar: explicit Lagrangian FEM for high-velocity impact of deformable solids.
!> init -> run -> finalize.
program udar
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use udar_kinds, only: rk, i8, max_path_len
  use udar_comms, only: comms_init, comms_finalize, comms_is_root, comms_size, comms_rank, comms_bcast_int, &
      halo_t, comms_max_int, comms_max_i8, comms_sum_int, comms_allgather_count, comms_allgatherv_int, comms_wtime, &
      comms_allgatherv_real
  use udar_distribution, only: distribute_domain
  use udar_fatal, only: fatal_all, exit_input
  use udar_log, only: log_info, log_warn, log_to_stderr
  use udar_files, only: is_directory, can_write_into, nearest_existing_parent
  use udar_version, only: program_version
  use udar_config, only: config_t, geometry_solid
  use udar_input_errors, only: input_errors_t, input_errors_report
  use udar_deck, only: deck_read, deck_where
  use udar_gmsh, only: gmsh_mesh_t, gmsh_read
  use udar_domain, only: domain_t, domain_bytes
  use udar_memory, only: peak_rss_bytes, rss_bytes
  use udar_setup, only: build_domain, init_state, count_bodies
  use udar_run, only: run_simulation, run_result_t
  use udar_element_passes, only: element_costs
  use udar_checkpoint, only: checkpoint_model_hash, checkpoint_mesh_hash, checkpoint_latest
  use udar_contact_model, only: contact_t, any_eroding
  use udar_contact_setup, only: build_contact
  use udar_contact_erosion, only: contact_eroding_surfaces
  use udar_contact, only: contact_distribute
  use udar_partition, only: partition_elements, partition_stats_t
  use udar_decomposition, only: rank_counts_t, decomposition_counts
  use udar_strings, only: itoa, fixed
  use udar_signals, only: signals_install
  implicit none

  type(config_t) :: cfg
  type(input_errors_t) :: errs
  type(gmsh_mesh_t) :: mesh
  type(domain_t) :: dom, local
  type(halo_t) :: halo
  type(contact_t) :: contacts
  type(run_result_t) :: res
  character(len=max_path_len) :: arg, deck_path
  logical :: check_only, ok
  character(len=:), allocatable :: msg
  character(len=512) :: line
  integer :: k, ios, n_bodies
  integer :: preview_ranks = 0    !< --ranks N: show the partition for N ranks (with --check)
  character(len=max_path_len) :: restart_arg = ''   !< --restart CHECKPOINT | auto
  real(rk) :: wall_limit_arg = 0.0_rk               !< --wall-limit S: overrides &run wall_limit
  character(len=:), allocatable :: pending, restart_path
  integer(i8) :: model_hash, mesh_hash, glob_bytes
  integer, allocatable :: weights(:)   !< cost weight of each global element, for a rebalance's partition
  integer :: rebalances, cycles_run
  real(rk) :: loop_seconds, wall_seconds, job_start

  ! first: a batch system's signal during set-up is kept, not fatal
  call signals_install()
  call comms_init()
  job_start = comms_wtime()
  check_only = .false.
  deck_path = ''
  pending = ''
  do k = 1, command_argument_count()
    call get_command_argument(k, arg)
    if (len(pending) > 0) then     ! the value of the option before
      select case (pending)
      case ('--ranks')
        read(arg, *, iostat=ios) preview_ranks
        if (ios /= 0 .or. preview_ranks < 1) call fatal_all(exit_input, '--ranks '//trim(arg)// &
                                                         ': expected a positive number of ranks')
      case ('--restart')
        restart_arg = arg
      case ('--wall-limit')
        read(arg, *, iostat=ios) wall_limit_arg
        if (ios /= 0 .or. wall_limit_arg <= 0.0_rk) call fatal_all(exit_input, '--wall-limit '//trim(arg)// &
                                                                 ': expected a positive number of seconds')
      end select
      pending = ''
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
    case ('--ranks', '--restart', '--wall-limit')
      if (k == command_argument_count()) call fatal_all(exit_input, trim(arg)//' needs a value (see udar --help)')
      pending = trim(arg)
    case default
      if (arg(1:1) == '-') call fatal_all(exit_input, 'unknown option '//trim(arg)//' (see udar --help)')
      if (len_trim(deck_path) > 0) call fatal_all(exit_input, 'more than one deck given: '//trim(deck_path)// &
                                              ' and '//trim(arg))
      deck_path = arg
    end select
  end do
  if (preview_ranks > 0 .and. .not. check_only) call fatal_all(exit_input, '--ranks goes with --check '// &
    '(a run uses the ranks mpirun gives it)')
  if (len_trim(deck_path) == 0) then
    call usage()
    call fatal_all(exit_input, 'no input deck given')
  end if

  if (check_only) call log_to_stderr()
  ! ---- input: every mistake in the deck and its mesh reported at once
  call deck_read(trim(deck_path), cfg, errs)
  if (errs%count() == 0) call check_output_directory()
  if (errs%count() == 0) call read_model()
  if (errs%count() > 0) then
    if (comms_is_root()) call input_errors_report(errs, error_unit)
    call fatal_all(exit_input, 'input deck '//trim(deck_path)//' has errors; nothing was run or written')
  end if
  call log_info(line)
  n_bodies = count_bodies(dom)
  if (n_bodies > 1 .and. contacts%n_interfaces == 0) then
    write(line, '(a,i0,a)') 'the mesh holds ', n_bodies, ' separate bodies and the deck no &contact: '// &
      'they will pass through each other'
    call log_warn(line)
  end if

  if (check_only) then
    if (comms_is_root()) write(output_unit, '(a)') cfg%resolved_text
    if (preview_ranks > 0) call report_partition(dom, preview_ranks)
    call log_info('deck '//trim(deck_path)//' is valid')
    call comms_finalize()
    stop
  end if

  if (wall_limit_arg > 0.0_rk) cfg%run%wall_limit = wall_limit_arg
  if (any_eroding(contacts) .and. cfg%run%dt_safety > 0.5_rk) call log_warn('&run dt_safety > 0.5 with an '// &
    'eroding &contact surface: on a 3 km/s eroding penetration at 0.7-0.9 slave nodes stay up to 0.02 of an element '// &
    'inside the master for a few cycles (up to 0.008 at 0.33-0.5; doc/validation.md 4s); 0.5 or less is recommended '// &
    'with erosion (contact without it runs at the elements'' own step, 4t)')
  call log_info('udar '//program_version//': '//trim(cfg%run%title))
  model_hash = checkpoint_model_hash(cfg%resolved_text)
  mesh_hash = checkpoint_mesh_hash(dom)
  restart_path = trim(restart_arg)
  if (restart_path == 'auto') then
    ! the newest readable checkpoint of this deck's case, or a fresh start
    restart_path = checkpoint_latest(trim(cfg%output%directory)//'/'//trim(cfg%output%case_name), &
                                     max(cfg%output%checkpoint_keep, 1))
    if (len(restart_path) == 0) call log_info('--restart auto: no checkpoint of this case yet; starting at t = 0')
  end if
  glob_bytes = domain_bytes(dom)
  ! a run is one segment, or several when &run rebalance_imbalance asks for
  ! a new partition: each ends with a checkpoint that the next, on a
  ! partition weighted by the elements' cost, restarts from (the results are
  ! those of one segment: they do not depend on the partition)
  rebalances = 0
  cycles_run = 0
  loop_seconds = 0.0_rk
  wall_seconds = 0.0_rk
  do
    call decompose(dom, local, halo, weights)
    local%time_blocks = cfg%run%rebalance_imbalance > 0.0_rk .and. comms_size() > 1
    call contact_distribute(contacts, local)
    if (rebalances == 0) call log_memory('start-up', local)
    call run_simulation(cfg, local, halo, contacts, restart_path, model_hash, mesh_hash, res, rebalances, job_start)
    cycles_run = cycles_run + res%cycles_run
    loop_seconds = loop_seconds + res%loop_seconds
    wall_seconds = wall_seconds + res%wall_seconds
    if (.not. res%rebalance) exit
    rebalances = rebalances + 1
    call gather_cost_weights(local, weights)
    restart_path = trim(res%checkpoint)
    ! the global mesh domain and the contact surfaces again, as at the start
    call read_model()
    if (errs%count() > 0) call fatal_all(exit_input, 'rebalance: the mesh could not be read again; the run '// &
                                         'goes on with: udar --restart '//trim(res%checkpoint)//' DECK')
    if (checkpoint_mesh_hash(dom) /= mesh_hash) call fatal_all(exit_input, 'rebalance: the mesh file '// &
      trim(cfg%mesh%file)//' changed during the run; the run goes on with its own mesh and: udar --restart '// &
      trim(res%checkpoint)//' DECK')
  end do
  call log_memory('run', local)
  write(line, '(a,i0,a,es12.5,a,es10.3,a)') 'udar: done: ', res%cycles, ' cycles to t = ', &
    res%time, ' s, energy error ', res%energy_error, ', '//fixed(wall_seconds, 2)//' s wall ('// &
    fixed(1.0e9_rk*loop_seconds/(real(local%n_global_elems, rk)*max(cycles_run, 1)), 1)// &
    ' ns per element-cycle); fields '//trim(res%field_file)//', history '//trim(res%history_file)
  if (rebalances > 0) line = trim(line)//'; '//itoa(rebalances)//' rebalance'//trim(merge('s', ' ', rebalances > 1))
  call log_info(line)
  call comms_finalize()

contains

  !> METIS partition on rank 0 (one answer for all), the local domain and
  !> halo of this rank, and the partition report. The global domain is freed
  !> before the local state is allocated (the start-up peak).
  subroutine decompose(glob, loc, halo, weights)
    type(domain_t), intent(inout) :: glob
    type(domain_t), intent(out) :: loc
    type(halo_t), intent(out) :: halo
    integer, allocatable, intent(in) :: weights(:)   !< if allocated: the elements' cost weights
    integer, allocatable :: part(:)
    type(partition_stats_t) :: stats
    integer :: n, bad
    msg = ''
    n = comms_size()
    allocate(part(glob%n_elems), source=0)
    bad = 0
    if (n > 1) then
      if (comms_is_root()) then
        if (allocated(weights)) then
          call partition_elements(glob%n_nodes, glob%el_conn, n, part, stats, ok, msg, weights)
        else
          call partition_elements(glob%n_nodes, glob%el_conn, n, part, stats, ok, msg)
        end if
        if (.not. ok) bad = 1
      end if
      if (comms_max_int(bad) /= 0) call fatal_all(exit_input, 'partition for '//itoa(n)//' ranks: '//msg)
      call comms_bcast_int(part)
      if (comms_is_root()) call log_partition(glob, part, n, stats)
      if (comms_is_root() .and. allocated(weights)) then
        write(line, '(a,f0.2,a,f6.3,a)') 'partition weighted by the elements'' measured cost (the dearest ', &
          maxval(weights)/10.0_rk, ' times the mean): weighted load imbalance ', stats%weighted_imbalance
        call log_info(line)
      end if
    end if
    call distribute_domain(glob, part, comms_rank(), loc, halo)
    deallocate(part)
    glob = domain_t()
    call init_state(loc)
  end subroutine

  !> Memory, largest rank: at start-up, the peak so far and what the domains
  !> hold (the local domains of all ranks, ghosts included, and the global
  !> mesh domain every rank builds while splitting it, glob_bytes); after
  !> the run, the resident memory (the steady footprint) and the process peak.
  !> Per global element, for `make bench` and doc/performance.md.
  subroutine log_memory(stage, loc)
    character(len=*), intent(in) :: stage
    type(domain_t), intent(in) :: loc
    integer(i8) :: peak, resident, local_bytes
    real(rk) :: ne
    peak = comms_max_i8(peak_rss_bytes())
    resident = comms_max_i8(rss_bytes())
    local_bytes = comms_sum_int(domain_bytes(loc))
    ne = real(max(loc%n_global_elems, 1), rk)
    if (stage == 'start-up') then
      write(line, '(a,f0.1,a,i0,a,i0,a,i0,a)') 'memory: start-up peak ', peak/1048576.0_rk, ' MiB = ', &
        nint(peak/ne), ' bytes per element (largest rank); domains ', nint(local_bytes/ne), ' bytes per '// &
        'element (all ranks), global mesh domain ', nint(glob_bytes/ne), ' bytes per element (each rank, '// &
        'freed before the run)'
    else
      write(line, '(a,f0.1,a,i0,a,f0.1,a,i0,a)') 'memory: resident after the run ', resident/1048576.0_rk, &
        ' MiB = ', nint(resident/ne), ' bytes per element, process peak ', peak/1048576.0_rk, ' MiB = ', &
        nint(peak/ne), ' bytes per element (largest rank)'
    end if
    call log_info(line)
  end subroutine

  !> The deck's mesh read into the global mesh domain dom and the contact
  !> surfaces (errors into errs); line: what the log says of the mesh.
  subroutine read_model()
    ! a 2D calculation reads triangles in surface groups and lines in curve groups
    call gmsh_read(trim(cfg%mesh%file), cfg%mesh%scale, mesh, ok, msg, dim=merge(3, 2, cfg%mesh%geometry == geometry_solid))
    if (.not. ok) then
      call errs%add(deck_where(cfg, 'mesh', 1, 'file')//': '//msg)
    else
      dom = domain_t()
      contacts = contact_t()
      call build_domain(cfg, mesh, dom, errs)
      if (errs%count() == 0) call build_contact(cfg, mesh, dom, contacts, errs)
      ! the eroding surfaces with each face's element (its corner opposite)
      if (errs%count() == 0) call contact_eroding_surfaces(contacts)
      write(line, '(a,i0,a,i0,a,i0,a)') 'mesh '//trim(cfg%mesh%file)//': ', mesh%n_nodes, ' nodes, ', &
        mesh%n_cells, trim(merge(' tetrahedra', ' triangles ', mesh%dim == 3))//', ', mesh%n_inverted, &
        ' reoriented at read time'
    end if
    mesh = gmsh_mesh_t()     ! the domain and the contact surfaces hold all that is needed of it
  end subroutine

  !> The cost weight of every global element: its measured cost
  !> (element_costs of the owned elements, gathered to every rank by global
  !> index) in tenths of the mean element's, at least 1 (the sum fits METIS's 32-bit
  !> weights up to 200 million elements).
  subroutine gather_cost_weights(loc, w)
    type(domain_t), intent(in) :: loc
    integer, allocatable, intent(inout) :: w(:)
    real(rk), allocatable :: cost(:), own_c(:), all_c(:), c(:)
    integer, allocatable :: own_g(:), all_g(:), counts(:)
    integer :: no
    real(rk) :: mean
    allocate(cost(loc%n_elems))
    call element_costs(loc, cost)
    no = size(loc%el_owned_list)
    own_c = cost(loc%el_owned_list)
    own_g = loc%el_gidx(loc%el_owned_list)
    allocate(counts(0:comms_size()-1))
    call comms_allgather_count(no, counts)
    allocate(all_c(sum(counts)), all_g(sum(counts)))
    call comms_allgatherv_real(own_c, counts, all_c)
    call comms_allgatherv_int(own_g, counts, all_g)
    allocate(c(loc%n_global_elems), source=0.0_rk)
    c(all_g) = all_c
    mean = max(sum(c)/max(size(c), 1), tiny(1.0_rk))
    if (allocated(w)) deallocate(w)
    w = max(1, nint(10.0_rk*c/mean))
  end subroutine

  !> udar --check --ranks N: the partition a run on N ranks would get.
  subroutine report_partition(dom, n)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: n
    integer, allocatable :: part(:)
    type(partition_stats_t) :: stats
    allocate(part(dom%n_elems))
    call partition_elements(dom%n_nodes, dom%el_conn, n, part, stats, ok, msg)
    if (.not. ok) call fatal_all(exit_input, 'partition for '//itoa(n)//' ranks: '//msg)
    call log_partition(dom, part, n, stats)
  end subroutine

  !> Edge cut, imbalance, what each rank owns and holds as ghosts, and the
  !> cost of the decomposition: redundant (ghost) element work and halo
  !> traffic (x and v, plus nodal J and p with anti-locking: 8 reals per
  !> ghost node and cycle).
  subroutine log_partition(dom, part, n, stats)
    type(domain_t), intent(in) :: dom
    integer, intent(in) :: part(:), n
    type(partition_stats_t), intent(in) :: stats
    type(rank_counts_t), allocatable :: counts(:)
    integer :: r
    real(rk) :: overhead, worst
    allocate(counts(0:n-1))
    call decomposition_counts(dom%el_conn, dom%nd_el_ptr, dom%nd_el, part, n, counts)
    write(line, '(a,i0,a,i0,a,f6.3)') 'partition over ', n, ' ranks (METIS k-way, element dual graph): '// &
      'edge cut ', stats%edge_cut, ' faces, load imbalance ', stats%imbalance
    call log_info(line)
    if (n <= 64) then
      call log_info('  rank  owned_elems  owned_nodes  ghost_elems  ghost_nodes')
      do r = 0, n - 1
        write(line, '(i6,4i13)') r, counts(r)%owned_elems, counts(r)%owned_nodes, counts(r)%ghost_elems, &
          counts(r)%ghost_nodes
        call log_info(line)
      end do
    end if
    overhead = 100.0_rk*sum(real(counts%ghost_elems, rk))/dom%n_elems
    worst = 100.0_rk*maxval(real(counts%ghost_elems, rk)/max(counts%owned_elems, 1))
    write(line, '(a,i0,a,f7.2,a,f7.2,a,i0,a,i0,a,f9.1,a)') 'decomposition cost over ', n, ' ranks: ghost '// &
      'element work +', overhead, ' % in all (worst rank +', worst, ' %); halo ', sum(counts%ghost_nodes), &
      ' ghost nodes in all, at most ', maxval(counts%ghost_nodes), ' on a rank (', &
      8.0_rk*8.0_rk*maxval(counts%ghost_nodes)/1024.0_rk, ' KiB received per cycle)'
    call log_info(line)
    if (any(counts%owned_elems == 0)) call log_warn('some ranks own no element (more ranks than the mesh '// &
      'can use); they only take part in the collective steps')
  end subroutine

  !> The output folder must exist as a writable directory or be creatable
  !> (its nearest existing parent a writable directory): found now, before
  !> anything runs, and by --check too.
  subroutine check_output_directory()
    character(len=:), allocatable :: dir, parent, where
    dir = trim(cfg%output%directory)
    if (is_directory(dir)) then
      if (can_write_into(dir)) return
      where = deck_where(cfg, 'output', 1, 'directory')
      call errs%add(where//': the folder exists but this user cannot write into it')
      return
    end if
    parent = nearest_existing_parent(dir)
    if (.not. is_directory(parent)) then
      where = deck_where(cfg, 'output', 1, 'directory')
      call errs%add(where//': cannot be created: '''//parent//''' is a file, not a folder')
    else if (.not. can_write_into(parent)) then
      where = deck_where(cfg, 'output', 1, 'directory')
      call errs%add(where//': cannot be created: this user cannot write into '''//parent//'''')
    end if
  end subroutine

  subroutine usage()
    call log_info('usage: [mpirun -np N] udar [--restart CKPT|auto] [--wall-limit S] DECK.nml')
    call log_info('       udar --check [--ranks N] DECK.nml | --help | --version')
    call log_info('  DECK.nml          run the namelist input deck (on as many MPI ranks as mpirun gives)')
    call log_info('  --restart CKPT    continue from checkpoint CKPT (any number of ranks); with "auto",')
    call log_info('                    from the newest checkpoint of the deck''s case, or from t = 0 if none')
    call log_info('  --wall-limit S    checkpoint and stop before S seconds of wall time (overrides &run wall_limit)')
    call log_info('  --check           validate the deck and its mesh, print the resolved deck, run nothing')
    call log_info('  --ranks N         with --check: show how the mesh would be split over N MPI ranks')
    call log_info('  --help            this text;  --version  the program version')
    call log_info('SIGUSR1 (also through mpirun, which forwards it), SIGTERM or SIGINT sent to the udar')
    call log_info('processes make a run checkpoint and stop (exit 0), as a wall-time limit does.')
    call log_info('Exit codes: 0 done (or stopped with a checkpoint), 1 input error, 2 the run went bad')
    call log_info('(physics), 3 I/O error (including a missing, damaged or foreign checkpoint).')
  end subroutine
end program udar
