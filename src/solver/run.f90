!> The time loop: explicit central difference in EPIC order (nodes, walls,
!> elements, forces), with output, energy balance and the checks that stop a
!> run that has gone bad (inverted element, NaN, energy blow-up) after
!> leaving a last field dump. Distributed: every rank advances its local
!> domain; halo exchanges bring the ghosts' kinematics and nodal averages,
!> and every global sum is exact, so the run is bitwise the same on any
!> number of ranks.
module udar_run
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use udar_kinds, only: rk, max_path_len
  use udar_config, only: config_t, geometry_axisymmetric, geometry_plane_strain, geometry_solid
  use udar_domain, only: domain_t, wall_t, gauge_node, gauge_element, gauge_point
  use udar_kinds, only: i8
  use udar_vectors, only: cross
  use udar_comms, only: comms_barrier, comms_wtime, comms_size, comms_min, comms_max, comms_min_int, comms_max_int, comms_max_i8, comms_is_root, &
      comms_sum_int, comms_allgather_count, comms_allgatherv_int, &
      comms_sum_exact, halo_t, comms_halo_exchange, comms_halo_exchange_scalar
  use udar_exact_sum, only: exact_limbs, exact_clear, exact_add, exact_value, exact_sum_of
  use udar_fatal, only: fatal, fatal_all, fatal_unless_all_ok, exit_physics, exit_io, log_error_here
  use udar_log, only: log_info, log_warn
  use udar_element_passes, only: element_volumes, element_update, nodal_pressures, element_time_steps, &
      element_forces_averaged, element_stiffness_bounds, nodal_stable_dt, nodal_reference_volumes, current_volume, &
      element_altitudes
  use udar_fracture, only: fracture_enabled, erosion_enabled, el_intact, el_eroded, erode_reasons, erode_strain, &
      erode_time_step, erode_inverted, erode_converted
  use udar_nodal, only: update_velocities, apply_velocity_conditions, apply_rigid_walls, apply_axis, update_positions, &
      keep_constrained_positions, restore_constrained_positions, walls_on_points
  use udar_particle_model, only: particles_t
  use udar_particle_driver, only: particles_init, particles_convert, particles_forces, particles_move, particles_finish_step, &
      particles_converting, particles_contact_work, particles_onto_planes
  use udar_strength, only: von_mises
  use udar_history, only: history_t, history_open, history_reopen, history_write, history_sync, history_close
  use udar_field_output, only: field_writer_t, fw_open, fw_reopen, fw_begin_step, fw_node_vector, fw_node_scalar, &
      fw_elem_scalar, fw_particles, particle_scalars, &
      fw_end_step, fw_close
  use udar_version, only: program_version
  use udar_run_state, only: run_state_t
  use udar_checkpoint, only: checkpoint_write, checkpoint_read
  use udar_signals, only: signal_received
  use udar_hash, only: hash_hex
  use udar_strings, only: itoa, fixed
  use udar_contact_model, only: contact_t
  use udar_contact, only: contact_enforce, contact_overlaps, contact_settle, contact_pressure, contact_keep_velocities, &
      contact_work, contact_extent, contact_add_particles, contact_refresh_masses
  use udar_contact_erosion, only: contact_erode
  use udar_eroded_voids, only: voids_t, voids_setup, voids_enforce, voids_mark_stale
  use udar_files, only: rename_file, remove_if_present, make_directories
  implicit none
  private
  public :: run_simulation, run_result_t

  !> history columns of each contact interface: normal and friction force,
  !> largest slip, deep slave nodes found, the force on the master side
  integer, parameter :: per_interface = 7
  integer, parameter :: n_base = 16          !< history columns before the parts'
  !> history columns of each part (LS-DYNA's matsum): kinetic energy, centre
  !> of mass, internal energy, plastic work, eroded energy, mass, momentum,
  !> mean velocity
  integer, parameter :: per_part = 14
  !> a gauge's state column: its element's (el_intact, el_fractured,
  !> el_eroded), or this once the element has become a particle
  integer, parameter :: gauge_particle = 3
  !> exact accumulators of each part: kinetic energy, mass moments (3), mass,
  !> internal energy, plastic work, eroded energy, momentum (3)
  integer, parameter :: part_sums = 11

  !> What a finished run reports back (for the summary and the caller).
  type :: run_result_t
    integer :: cycles = 0
    real(rk) :: time = 0.0_rk, energy_error = 0.0_rk, wall_seconds = 0.0_rk
    logical :: stopped = .false.                !< stopped early (wall limit, signal) after a checkpoint
    !> stopped after a checkpoint to be repartitioned (&run rebalance_imbalance):
    !> the caller restarts from checkpoint on a partition weighted by cost
    logical :: rebalance = .false.
    character(len=max_path_len) :: checkpoint = ''   !< the last checkpoint written
    integer :: cycles_run = 0                   !< cycles of this call (a restart's: since the checkpoint)
    real(rk) :: loop_seconds = 0.0_rk           !< wall time of this call's cycle loop
    character(len=max_path_len) :: field_file = '', history_file = ''
  end type

  !> Energy and momentum balance at one instant (global).
  type :: balance_t
    real(rk) :: kinetic = 0, internal = 0, plastic = 0, wall_work = 0, total = 0, error = 0
    real(rk) :: contact_work = 0             !< J, work of the contact impulses (dissipation: negative)
    real(rk) :: momentum(3) = 0, wall_force = 0
    real(rk) :: angular_momentum(3) = 0      !< kg m2/s, sum m x x v about the centre of mass
    real(rk) :: eroded_energy = 0            !< J, internal energy of the eroded elements (in total)
    integer :: n_fractured = 0, n_eroded = 0 !< elements fractured (eroded ones included), eroded
    !> particles (eroded = 'particles'): how many, their mass, kinetic and
    !> internal energy (in kinetic and internal too), and the kinetic
    !> energy made heat at conversion (J)
    integer :: n_particles = 0
    real(rk) :: particle_mass = 0, particle_kinetic = 0, particle_internal = 0, conversion_heat = 0
    real(rk), allocatable :: contact_normal(:), contact_friction(:)   !< N, per interface
    real(rk), allocatable :: contact_slip(:)                          !< m/s, per interface
    real(rk), allocatable :: contact_deep(:)                          !< slave nodes found inside a master element, per interface
    real(rk), allocatable :: contact_force(:,:)                       !< N, (3, interfaces) on the master side
    real(rk), allocatable :: part_ke(:), part_com(:,:), part_mass(:)
    real(rk), allocatable :: part_internal(:), part_plastic(:), part_eroded(:), part_momentum(:,:)
    real(rk), allocatable :: gauge(:)      !< the gauges' values, in history column order
    integer(i8), allocatable :: acc(:,:)   !< exact accumulators, one column per summed quantity
  end type

  !> Exact accumulators of the rigid walls: work since the start (all walls)
  !> and each wall's normal impulse of the current cycle; local to the rank
  !> until a balance reduces them.
  type :: wall_sums_t
    integer(i8) :: work(0:exact_limbs) = 0
    integer(i8) :: contact_work(0:exact_limbs) = 0   !< J, work of the contact impulses since the start
    integer(i8), allocatable :: impulse(:,:)
    real(rk) :: dt_v = 1                    !< s, interval of the last impulse
  end type

contains

  !> Runs the deck from t = 0, or from a checkpoint (restart_path not empty).
  !> model_hash, mesh_hash: what a checkpoint must match to be accepted.
  !> rebalances_before: rebalances earlier in this process; each doubles
  !> the cycles a segment runs before its balance is judged (a partition
  !> whose weights miss the cost is not redone every few cycles).
  !> job_start: comms_wtime() when the job started (&run wall_limit counts
  !> from it).
  subroutine run_simulation(cfg, dom, halo, ct, restart_path, model_hash, mesh_hash, res, rebalances_before, &
                            job_start)
    type(config_t), intent(in) :: cfg
    type(domain_t), intent(inout) :: dom
    type(halo_t), intent(inout) :: halo
    type(contact_t), intent(inout) :: ct
    character(len=*), intent(in) :: restart_path
    integer(i8), intent(in) :: model_hash, mesh_hash
    type(run_result_t), intent(out) :: res
    integer, intent(in) :: rebalances_before
    real(rk), intent(in) :: job_start
    type(field_writer_t) :: fw
    type(history_t) :: hist
    type(balance_t) :: bal
    type(wall_sums_t) :: walls
    type(run_state_t) :: st
    type(particles_t) :: pt
    type(voids_t) :: vd
    integer(i8), allocatable :: wall_work_dummy(:), wall_impulse_dummy(:,:)   !< the walls' sums of particles off the root rank
    integer(i8), allocatable :: sym_impulse_dummy(:,:)   !< the symmetry planes' impulses on particles (not booked)
    real(rk) :: dt_conv
    integer :: n_conv
    real(rk), allocatable :: work_svm(:), work_rho(:), row(:), work_node(:,:), work_elem(:), work_step(:)
    real(rk), allocatable :: x_constrained(:,:)   !< positions of the constrained nodes before the contact pass
    real(rk) :: dt, dt_v, wall0, elapsed, loop0, last_print_wall, left, ckpt_seconds, cycle_seconds, &
                contact_seconds, dt_local, imbalance
    integer :: bad, bad_avg, bad_gidx, bad_tag, bad_part, last_print_cycle, no, k, stop_code, cycles_run, n_slave, &
               dt_node, dt_warn_level
    integer :: n_eroded_now(erode_reasons), n_eroded_by(erode_reasons)
    logical, allocatable :: owned_gone(:)                  !< owned elements already passed to the contact surfaces
    integer, allocatable :: new_gidx(:), all_gidx(:), erosion_counts(:)
    logical :: ok, done, history_due, print_due, full_balance, stopping, eroded_any, fracture_on, fields_due, ended, last_step
    integer, parameter :: balance_interval = 10
    !> a rebalance is judged on at least this many cycles of measured work
    integer, parameter :: rebalance_cycles = 100
    ! the elements' energy (internal + eroded) at the end of a cycle, kept for
    ! the next cycle's balance: the half-step velocities' kinetic energy
    ! belongs to the middle of the step, so the balance takes the mean of
    ! the step's two ends (theory.md 10)
    real(rk) :: u_prev, e_mid
    integer :: u_prev_cycle
    character(len=:), allocatable :: errmsg, base, why
    character(len=256) :: line
    character(len=300), allocatable :: overlap_lines(:)

    wall0 = comms_wtime()
    fracture_on = any_fracture(dom)
    pt%enabled = particles_converting(dom)
    no = size(dom%el_owned_list)
    base = trim(cfg%output%directory)//'/'//trim(cfg%output%case_name)
    res%field_file = base//'.h5'
    res%history_file = base//'_history.csv'
    allocate(work_node(dom%n_owned_nodes,3))
    allocate(x_constrained(3, size(dom%sym_nodes) + size(dom%fixed_nodes)))
    allocate(row(size(history_columns(dom, ct))))
    allocate(wall_work_dummy(0:exact_limbs), wall_impulse_dummy(0:exact_limbs, size(dom%walls)), &
             sym_impulse_dummy(0:exact_limbs, size(dom%sym_walls)))
    allocate(walls%impulse(0:exact_limbs, size(dom%walls)))
    walls%impulse = 0
    st%model_hash = model_hash
    st%mesh_hash = mesh_hash
    why = ''

    if (len_trim(restart_path) > 0) then
      ! ---- restart: the checkpoint is checked before any output is touched
      call checkpoint_read(trim(restart_path), dom, st, pt, ok, errmsg)
      if (ok .and. st%model_hash /= model_hash) then
        ok = .false.
        errmsg = 'checkpoint '//trim(restart_path)//' belongs to another deck (model hash '// &
          hash_hex(st%model_hash)//', this deck '//hash_hex(model_hash)//'; only &run and &output may '// &
          'change between a run and its restart)'
      else if (ok .and. st%mesh_hash /= mesh_hash) then
        ok = .false.
        errmsg = 'checkpoint '//trim(restart_path)//' belongs to another mesh (mesh hash '// &
          hash_hex(st%mesh_hash)//', this mesh '//hash_hex(mesh_hash)//')'
      end if
      if (.not. ok) call fatal_all(exit_io, errmsg//'; nothing was written')
      if (st%t >= cfg%run%t_end*(1.0_rk - 1.0e-12_rk)) then
        write(line, '(a,es12.5,a,es12.5,a)') 'checkpoint '//trim(restart_path)//' is at t = ', st%t, &
          ' s, the end of the run (t_end = ', cfg%run%t_end, ' s): nothing to do'
        call log_info(line)
        call write_status(base, 'complete', '')
        res%time = st%t
        res%cycles = st%cycle
        return
      end if
      ! a run that ended by the kinetic-energy criterion checkpointed at its end
      ended = .false.
      if (cfg%run%end_kinetic_fraction > 0.0_rk .and. mod(st%cycle, balance_interval) == 0) then
        call compute_balance(dom, walls, ct, pt, bal)
        ended = bal%kinetic < cfg%run%end_kinetic_fraction*st%ke_peak
      end if
      if (ended) then
        call log_info('checkpoint '//trim(restart_path)//' is at the end of the event (kinetic energy below '// &
                      'end_kinetic_fraction of its peak): nothing to do')
        call write_status(base, 'complete', '')
        res%time = st%t
        res%cycles = st%cycle
        return
      end if
      call reopen_outputs()
      allocate(work_svm(no), work_rho(no), work_elem(no), work_step(dom%n_elems))   ! after the open: see below
      ! the time step comes from the checkpoint; the bounds only for output until the first update
      call element_stiffness_bounds(dom)
      ! each rank's accumulator adds to the global sum: the saved total goes to one rank
      walls%work = 0
      walls%contact_work = 0
      if (comms_is_root()) walls%work = st%wall_work
      if (comms_is_root()) walls%contact_work = st%contact_work
      u_prev = element_energy(dom, pt)
      u_prev_cycle = st%cycle
      write(line, '(a,i0,a,es12.5,a,i0,a)') 'restart from '//trim(restart_path)//' at cycle ', st%cycle, &
        ', t = ', st%t, ' s, on ', comms_size(), trim(merge(' rank ', ' ranks', comms_size() == 1))
      call log_info(line)
    else
      call open_outputs()
      ! the field work arrays, allocated once the field file is open, take
      ! the memory its opening freed (the connectivity copies) instead of
      ! adding to the process peak
      allocate(work_svm(no), work_rho(no), work_elem(no), work_step(dom%n_elems))
      call contact_overlaps(ct, dom, overlap_lines)
      do k = 1, size(overlap_lines)
        call log_info(trim(overlap_lines(k)))
      end do
      call element_stiffness_bounds(dom)
      call nodal_stable_dt(dom, st%dt_stable, dt_node)
      st%dt_stable = comms_min(st%dt_stable)
      st%dt0 = st%dt_stable
      call compute_balance(dom, walls, ct, pt, bal)
      st%e0 = bal%kinetic + bal%internal
      st%e_ref = max(abs(st%e0), tiny(1.0_rk))
      u_prev = bal%internal + bal%eroded_energy
      u_prev_cycle = st%cycle
      call write_fields(fw, dom, st%t, st%cycle, work_svm, work_rho)
      st%field_steps = st%field_steps + 1
      st%ke_peak = bal%kinetic
      call history_row(0.0_rk)
      st%history_rows = st%history_rows + 1
      st%t_next_field = cfg%output%dt_field
      st%t_next_hist = cfg%output%dt_history
      st%t_next_checkpoint = cfg%output%dt_checkpoint
    end if
    ! erosion: elements of eroding materials whose step collapses; the
    ! nodal reference volumes without the elements already eroded (restart)
    dom%erode_dt_limit = cfg%numerics%erode_dt_ratio*st%dt0
    dom%keep_volumes = any(erosion_enabled(dom%mat))
    dom%keep_altitudes = ct%n_interfaces > 0
    pt%use_shear_switch = cfg%numerics%sph_viscosity_switch
    call particles_init(pt, dom)
    if (allocated(ct%part_voids)) call voids_setup(vd, dom, ct%part_voids)
    ! (a restart's particles are contact nodes, and the nodes' masses without their elements)
    if (pt%n > 0) then
      call contact_refresh_masses(ct, dom)
      call contact_add_particles(ct, pt, placed=.true.)
    end if
    call nodal_reference_volumes(dom, rebase=.false.)
    ! the altitudes of the last element pass (a restart reads them: slave
    ! nodes settled after that pass have moved since)
    if (len_trim(restart_path) == 0) call element_altitudes(dom)
    n_eroded_by = 0
    ! eroding contact surfaces: the elements already eroded (restart)
    if (ct%n_tets > 0) then
      allocate(owned_gone(no), source=.false.)
      allocate(new_gidx(no), all_gidx(dom%n_global_elems), erosion_counts(0:comms_size()-1))
      call share_erosion(.true., .false.)
    end if
    write(line, '(a,i0,a,i0,a,es10.3,a)') 'start: ', dom%n_global_elems, ' elements, ', dom%n_global_nodes, &
      ' nodes, stable step ', st%dt_stable, ' s'
    call log_info(line)
    if (dom%geometry == geometry_axisymmetric) call log_info('axisymmetric (x = r, y the axis): the masses, '// &
      'energies, momenta and forces of the history are those of the full revolution (2 pi rad)')
    if (dom%geometry == geometry_plane_strain) call log_info('plane strain: the masses, energies, momenta and '// &
      'forces of the history are per metre of thickness (z)')
    ! the stable step is watched from here on: the first warning below
    ! dt_warn_ratio of the starting step, then one per further factor of 10
    dt_warn_level = 0

    done = .false.
    stopping = .false.
    loop0 = comms_wtime()
    last_print_wall = loop0
    last_print_cycle = st%cycle
    cycles_run = 0
    ckpt_seconds = -1.0_rk      ! until measured: twice a field step's cost
    contact_seconds = 0.0_rk
    do while (.not. done)
      ! ---- time step: the stable one, or what is left to t_end
      call next_step(dt, last_step)
      if (last_step) done = .true.
      dt_v = 0.5_rk*(st%dt_old + dt)
      ! ---- nodes: v(n+1/2), conditions, walls, x(n+1); then the ghosts' from their owners
      call contact_keep_velocities(ct, dom, 1)
      call contact_extent(ct, dom)
      call update_velocities(dom, dt_v)
      call apply_velocity_conditions(dom)
      do k = 1, size(dom%walls)
        call exact_clear(walls%impulse(:,k))
      end do
      call apply_rigid_walls(dom, dt, walls%work, walls%impulse)
      call apply_axis(dom, dt, walls%work)
      ! the particles, every one on every rank: forces at x(n), the walls
      ! (their sums on one rank), x(n+1); their state at n+1 after the contact
      if (pt%n > 0) then
        call particles_forces(pt, dom%sym_walls, dom%mat, dt_v)
        call walls_on_particles(dom%walls, walls%impulse, wall_impulse_dummy)
        ! the symmetry planes as frictionless walls (their impulses are no wall's force)
        call walls_on_particles(dom%sym_walls, sym_impulse_dummy, sym_impulse_dummy)
        call particles_move(pt, dt)
      end if
      walls%dt_v = dt_v
      call update_positions(dom, dt)
      elapsed = comms_wtime()
      call contact_keep_velocities(ct, dom, 2)
      if (vd%on) then
        ! the holes erosion left may close but not turn inside out (&contact
        ! voids), from every local node's x(n+1) and v(n+1/2): the ghosts'
        ! from their owners first; the contact's work takes in its changes
        call comms_halo_exchange(halo, dom%nd_x, dom%nd_v)
        call voids_enforce(vd, dom, halo, dt)
      end if
      if (ct%n_interfaces > 0) call keep_constrained_positions(dom, x_constrained)
      call contact_enforce(ct, dom, dt, pt)
      ! the contact pass knows no velocity conditions: they hold again after it
      ! (and no particle is left behind a symmetry plane)
      if (ct%n_interfaces > 0) call restore_constrained_positions(dom, x_constrained)
      if (ct%n_interfaces > 0 .and. pt%n > 0) call particles_onto_planes(pt, dom%sym_walls)
      call contact_work(ct, dom, walls%contact_work)
      if (pt%n > 0 .and. ct%n_interfaces > 0 .and. comms_is_root()) call particles_contact_work(pt, walls%contact_work)
      ! the particles' state at n+1 from the velocities the contact leaves
      if (pt%n > 0) call particles_finish_step(pt, dom, dt)
      contact_seconds = contact_seconds + (comms_wtime() - elapsed)
      call comms_halo_exchange(halo, dom%nd_x, dom%nd_v)
      st%t = st%t + dt
      st%cycle = st%cycle + 1
      cycles_run = cycles_run + 1
      st%dt_old = dt
      ! ---- elements: stress(n+1), forces(n+1); the nodal sums (J, p, f) in the
      ! element passes, each node as soon as its last element is done
      if (dom%anti_locking) then
        call element_volumes(dom)
        call comms_halo_exchange_scalar(halo, dom%nd_j)
      end if
      call element_update(dom, dt, bad, bad_avg, n_eroded_now, eroded_any, st%dt_stable, dt_node)
      n_eroded_by = n_eroded_by + n_eroded_now
      ! eroded elements of converting materials become particles; the step
      ! then respects the nodes that lost their mass
      if (pt%enabled) then
        call particles_convert(pt, dom, eroded_any, n_conv, dt_conv)
        st%dt_stable = min(st%dt_stable, dt_conv)
        if (n_conv > 0) then
          call contact_refresh_masses(ct, dom)
          call contact_add_particles(ct, pt)
        end if
      end if
      if (eroded_any) then
        call voids_mark_stale(vd)
        call nodal_reference_volumes(dom, rebase=dom%anti_locking)
        ! the nodal pressures again with the new reference volumes
        if (dom%anti_locking) call nodal_pressures(dom)
      end if
      if (ct%n_tets > 0) call share_erosion(sum(n_eroded_now) > 0, .true.)
      ! the lowest global id that inverted itself, else the lowest whose nodal
      ! average did: one reduction a cycle (keys above n_global_elems are the latter)
      bad_gidx = entry_or_huge(dom%el_gidx, bad)
      if (bad_gidx == huge(1) .and. bad_avg /= 0) bad_gidx = dom%n_global_elems + dom%el_gidx(bad_avg)
      bad_gidx = comms_min_int(bad_gidx)
      if (bad_gidx /= huge(1)) then
        if (bad_gidx > dom%n_global_elems) bad_gidx = bad_gidx - dom%n_global_elems
        call write_fields(fw, dom, st%t, st%cycle, work_svm, work_rho)
        call fw_close(fw); call history_close(hist)
        k = findloc(dom%el_gidx, bad_gidx, dim=1)
        bad_tag = comms_min_int(entry_or_huge(dom%el_id, k))
        bad_part = comms_min_int(entry_or_huge(dom%el_part, k))
        write(line, '(a,i0,a,i0,a,es14.7,a)') 'element ', bad_tag, ' (part '''// &
          trim(dom%part_name(bad_part))//''') inverted (volume <= 0) at cycle ', &
          st%cycle, ', time ', st%t, ' s; last state written to '//trim(res%field_file)
        call write_status(base, 'failed', line)
        call fatal_all(exit_physics, line)
      end if
      if (dom%anti_locking) then
        call comms_halo_exchange_scalar(halo, dom%nd_p)
        call element_forces_averaged(dom)
      end if
      if (pt%n > 0) st%dt_stable = min(st%dt_stable, pt%dt_stable)
      dt_local = st%dt_stable
      st%dt_stable = comms_min(st%dt_stable)
      if (cfg%run%dt_warn_ratio > 0.0_rk) then
        if (st%dt_stable < cfg%run%dt_warn_ratio*st%dt0/10.0_rk**dt_warn_level) call warn_small_step()
      end if
      if (st%cycle >= cfg%run%max_cycles) done = .true.

      ! ---- balance, checks, output
      history_due = history_due_at(st%t, done)
      print_due = print_due_at(st%cycle, done)
      ! the balance costs a pass over the mesh: every few cycles is enough to
      ! catch a blow-up, and between records the energies alone will do
      full_balance = history_due .or. print_due
      if (full_balance .or. mod(st%cycle, balance_interval) == 0) then
        if (full_balance) then
          call compute_balance(dom, walls, ct, pt, bal)
        else
          call compute_energies(dom, walls, pt, bal)
        end if
        e_mid = balance_energy(bal, u_prev, u_prev_cycle == st%cycle - 1)
        ! a deck that starts at rest (no energy) measures against the largest
        ! energy seen: energy from nothing then reads 1, not 1e303
        if (st%e0 == 0.0_rk) st%e_ref = max(st%e_ref, abs(e_mid))
        bal%error = (e_mid - bal%wall_work - bal%contact_work - st%e0)/max(st%e_ref, bal%kinetic)
        u_prev = bal%internal + bal%eroded_energy
        u_prev_cycle = st%cycle
      end if
      ! ---- end of the event: the kinetic energy below a share of its peak
      ! (looked at on the balance cycles only, so &run cycle_print cannot change the answer)
      ended = .false.
      if (mod(st%cycle, balance_interval) == 0) then
        st%ke_peak = max(st%ke_peak, bal%kinetic)
        if (.not. done .and. bal%kinetic < cfg%run%end_kinetic_fraction*st%ke_peak) then
          ended = .true.
          done = .true.
          history_due = .true.
          print_due = .true.
          ! the last row and line need the whole balance (the same energies, bitwise)
          if (.not. full_balance) call compute_balance(dom, walls, ct, pt, bal)
        end if
      end if
      if (.not. ieee_is_finite(bal%total) .or. abs(bal%error) > cfg%run%energy_error_limit) then
        call write_fields(fw, dom, st%t, st%cycle, work_svm, work_rho)
        call fw_close(fw); call history_close(hist)
        write(line, '(a,es11.3e3,a,i0,a,es14.7,a)') 'energy balance lost (error ', bal%error, ') at cycle ', &
          st%cycle, ', time ', st%t, ' s; '//hot_spot(dom)//'; last state written to '//trim(res%field_file)
        call write_status(base, 'failed', line)
        call fatal_all(exit_physics, line)
      end if
      if (history_due) then
        call history_row(dt)
        st%history_rows = st%history_rows + 1
        call advance(st%t_next_hist, cfg%output%dt_history)
      end if
      fields_due = done .or. (cfg%output%dt_field > 0.0_rk .and. st%t >= st%t_next_field*(1.0_rk - 1.0e-12_rk))
      if (fields_due) then
        elapsed = comms_wtime()
        call write_fields(fw, dom, st%t, st%cycle, work_svm, work_rho)
        st%field_steps = st%field_steps + 1
        if (ckpt_seconds < 0.0_rk) ckpt_seconds = 2.0_rk*(comms_wtime() - elapsed)
        call advance(st%t_next_field, cfg%output%dt_field)
      end if
      ! ---- a wall-time limit or a batch system's signal: checkpoint and stop
      ! (polled every few cycles; the ranks agree on the verdict)
      if (mod(st%cycle, balance_interval) == 0 .and. .not. done) then
        cycle_seconds = (comms_wtime() - loop0)/max(cycles_run, 1)
        stop_code = 0
        if (signal_received() /= 0) stop_code = 1
        if (cfg%run%wall_limit > 0.0_rk) then
          ! stop while there is time for the checkpoint and a few more cycles
          if (comms_wtime() - job_start + max(ckpt_seconds, 0.0_rk) + (balance_interval + 1)*cycle_seconds &
              + 1.0_rk >= cfg%run%wall_limit) stop_code = max(stop_code, 2)
        end if
        stop_code = comms_max_int(stop_code)
        if (stop_code > 0) then
          stopping = .true.
          done = .true.
          why = merge('a termination signal', 'the wall-time limit ', stop_code == 1)
        else if (cfg%run%rebalance_imbalance > 0.0_rk .and. comms_size() > 1 .and. &
                 cycles_run >= rebalance_cycles*2**min(rebalances_before, 20)) then
          ! the slowest rank's element work (its blocks' measured time, no
          ! waiting for other ranks) over the mean: the same verdict on
          ! every rank, from two reductions
          imbalance = real(comms_max_i8(sum(dom%blk_ticks)), rk)*comms_size()/ &
                      max(real(comms_sum_int(sum(dom%blk_ticks)), rk), 1.0_rk) - 1.0_rk
          if (imbalance > cfg%run%rebalance_imbalance) then
            stopping = .true.
            done = .true.
            res%rebalance = .true.
            why = 'a rebalance'
          end if
        end if
      end if
      ! ---- checkpoints: at their interval, at the end and when stopping early
      if (stopping .or. (cfg%output%dt_checkpoint > 0.0_rk .and. &
          (done .or. st%t >= st%t_next_checkpoint*(1.0_rk - 1.0e-12_rk)))) then
        call advance(st%t_next_checkpoint, cfg%output%dt_checkpoint)
        call write_checkpoint()
      end if
      ! the last picture of a stopped run is its last state: a history row
      ! and a field step after the checkpoint (a restart drops them and goes on
      ! as if never stopped)
      if (stopping) then
        ! (stops are decided on balance cycles: bal is this cycle's, whole
        ! once the energies alone are completed: the same energies, bitwise)
        if (.not. full_balance) call compute_balance(dom, walls, ct, pt, bal)
        if (.not. history_due) call history_row(dt)
        if (.not. fields_due) call write_fields(fw, dom, st%t, st%cycle, work_svm, work_rho)
      end if
      if (print_due .and. .not. stopping) then
        ! wall time left at the current step size and the recent cost of a cycle
        ! (the step shrinks as elements distort, so an average over the run says too little)
        elapsed = comms_wtime()
        left = (elapsed - last_print_wall)/max(st%cycle - last_print_cycle, 1)*max(cfg%run%t_end - st%t, 0.0_rk)/dt
        last_print_wall = elapsed
        last_print_cycle = st%cycle
        write(line, '(a,i8,a,es11.4,a,es10.3,a,es10.2,a,f9.1,a)') 'cycle', st%cycle, '  t ', st%t, ' s  dt ', dt, &
          ' s  energy error ', bal%error, '  wall left ', left, ' s'
        call log_info(line)
        if (fracture_on) then
          write(line, '(a,i0,a,i0,a,es10.3,a)') '         fracture: ', bal%n_fractured, ' elements fractured, ', &
            bal%n_eroded, ' eroded (', bal%eroded_energy, ' J of internal energy eroded)'
          if (pt%enabled) write(line, '(a,i0,a,i0,a,i0,a,es10.3,a,i0,a)') '         fracture: ', bal%n_fractured, &
            ' elements fractured or converted, ', bal%n_eroded, ' eroded, become ', pt%n, ' particles (', &
            bal%particle_mass, ' kg; ', count(pt%strong(1:pt%n)), ' keep their strength)'
          call log_info(line)
        end if
        do k = 1, ct%n_interfaces
          if (ct%ifc(k)%n_active == 0) cycle
          write(line, '(a,i0,a,es10.3,a,es10.3,a)') '         contact '//trim(ct%ifc(k)%name)//': ', &
            ct%ifc(k)%n_active, ' slave nodes corrected, deepest ', ct%ifc(k)%max_depth, ' m, normal force ', &
            bal%contact_normal(k), ' N'
          call log_info(line)
        end do
      end if
      ! the next cycle's balance takes this cycle's end: kept when it is due
      if (.not. done .and. u_prev_cycle /= st%cycle) then
        if (balance_due_next()) then
          u_prev = element_energy(dom, pt)
          u_prev_cycle = st%cycle
        end if
      end if
    end do
    call fw_close(fw)
    call history_close(hist)
    if (res%rebalance) then
      write(line, '(a,i0,a,es12.5,a)') 'rebalance at cycle ', st%cycle, ', t = ', st%t, &
        ' s: the slowest rank''s element work exceeds the mean by '//fixed(imbalance, 3)// &
        ' (&run rebalance_imbalance '//real_text(cfg%run%rebalance_imbalance, 3)//'); repartitioning through '// &
        checkpoint_path(st%checkpoints_written)
      call log_info(line)
    else if (stopping) then
      write(line, '(a,i0,a,es12.5,a)') 'stopped by '//trim(why)//' at cycle ', st%cycle, ', t = ', st%t, &
        ' s; continue with: udar --restart '//checkpoint_path(st%checkpoints_written)//' DECK'
      call log_info(line)
      call write_status(base, 'checkpointed', checkpoint_path(st%checkpoints_written))
    else if (ended) then
      line = 'the kinetic energy ('//real_text(bal%kinetic, 3)//' J) fell below end_kinetic_fraction of its '// &
        'peak ('//real_text(st%ke_peak, 3)//' J) at cycle '//itoa(st%cycle)//', t = '//real_text(st%t, 5)// &
        ' s: the event is over; run ended'
      call log_info(line)
      call write_status(base, 'complete', line)
    else if (st%t < cfg%run%t_end*(1.0_rk - 1.0e-12_rk)) then
      call write_status(base, 'max_cycles', '')
    else
      call write_status(base, 'complete', '')
    end if
    if (fracture_on) then
      do k = 1, erode_reasons
        n_eroded_by(k) = int(comms_sum_int(int(n_eroded_by(k), i8)))
      end do
      write(line, '(a,i0,a,a,i0,a,i0,a,i0,a,i0,a)') 'fracture: ', bal%n_fractured, ' elements fractured', &
        trim(merge(' or converted', '             ', pt%enabled))//', ', bal%n_eroded, ' eroded; in this run ', &
        n_eroded_by(erode_strain), ' by strain, ', n_eroded_by(erode_time_step), ' by time step, ', &
        n_eroded_by(erode_inverted), ' inverted within a step'
      if (n_eroded_by(erode_converted) > 0) line = trim(line)//', '//itoa(n_eroded_by(erode_converted))// &
        ' intact past eps_convert (particles with their strength)'
      call log_info(line)
    end if
    if (ct%n_interfaces > 0) then
      n_slave = 0
      do k = 1, ct%n_interfaces
        n_slave = n_slave + size(ct%ifc(k)%slave)
      end do
      line = 'contact: '//fixed(contact_seconds, 3)//' s ('// &
        fixed(100.0_rk*contact_seconds/max(comms_wtime() - loop0, tiny(1.0_rk)), 1)//' % of the cycle loop), '// &
        itoa(n_slave)//' slave nodes, '//fixed(1.0e9_rk*contact_seconds/(real(n_slave, rk)*max(cycles_run, 1)), 1)// &
        ' ns per slave node-cycle'
      call log_info(line)
      if (vd%on) call log_info('         contact: closed voids: '//itoa(int(comms_sum_int(vd%held_total)))// &
        ' held from turning inside out (eroded elements, summed over the cycles)')
      ! the slowest rank's: what a rank waits for
      line = '         contact: of which exchanges '//fixed(comms_max(ct%seconds_exchange), 3)// &
        ' s, the search for each rank''s share '//fixed(comms_max(ct%seconds_search), 3)// &
        ' s, the matching of each rank''s sets '//fixed(comms_max(ct%seconds_matching), 3)// &
        ' s, returns (every rank) '//fixed(comms_max(ct%seconds_replicated), 3)// &
        ' s (the slowest rank''s; with the settling after erosion)'
      call log_info(line)
      do k = 1, ct%n_interfaces
        write(line, '(a,i0,a,i0,a)') '         contact '//trim(ct%ifc(k)%name)//': full searches in ', &
          ct%ifc(k)%full_searches, ' of ', ct%ifc(k)%passes, ' passes (local tracking in the others)'
        call log_info(line)
        write(line, '(a,f0.1,a,i0,a,i0,a)') '         contact '//trim(ct%ifc(k)%name)//': velocity matching ', &
          real(ct%ifc(k)%sweeps, rk)/max(ct%ifc(k)%passes, 1), ' sweeps a pass on average; ', &
          ct%ifc(k)%sweep_limit_hits, ' passes ended at iterations = ', ct%ifc(k)%iterations, ' unconverged'
        call log_info(line)
        if (ct%ifc(k)%valleys) then
          write(line, '(a,i0,a)') '         contact '//trim(ct%ifc(k)%name)//': ', ct%ifc(k)%valley_total, &
            ' slave nodes matched to a valley''s second face (summed over the passes)'
          call log_info(line)
        end if
        if (ct%ifc(k)%edges) then
          write(line, '(a,i0,a,es10.3,a)') '         contact '//trim(ct%ifc(k)%name)//': ', &
            ct%ifc(k)%edge_contacts_total, ' edge-to-edge corrections, the deepest crossing ', &
            ct%ifc(k)%edge_max_depth, ' m'
          call log_info(line)
        end if
        if (ct%ifc(k)%deep_passes > 0) then
          write(line, '(a,i0,a,i0,a,es10.3,a,f0.3,a)') '         contact '//trim(ct%ifc(k)%name)//': ', &
            ct%ifc(k)%deep_total, ' slave nodes found inside a master element (deeper than the search margin) in ', &
            ct%ifc(k)%deep_passes, ' passes, the deepest ', ct%ifc(k)%deep_max, ' m (', &
            ct%ifc(k)%deep_max/ct%ifc(k)%h_mean, ' of the mean master edge)'
          call log_info(line)
        end if
        if (ct%ifc(k)%sweep_limit_hits > 0) call log_warn('contact '//trim(ct%ifc(k)%name)// &
          ': the velocity matching did not converge in '//itoa(ct%ifc(k)%sweep_limit_hits)// &
          ' passes (raise &contact iterations): their result depends on the order of the nodes')
      end do
      if (ct%particles_inside > 0) then
        write(line, '(a,i0,a,es10.3,a)') '         contact: ', ct%particles_inside, &
          ' particles made inside a master body were put on its surface (the deepest ', ct%particle_inside_deepest, ' m)'
        call log_info(line)
      end if
      if (ct%particles_left_inside > 0) call log_warn('contact: '//itoa(ct%particles_left_inside)// &
        ' particles were made inside a master body farther than three mean master edges from its surface and left there')
    end if
    res%stopped = stopping
    if (st%checkpoints_written > 0) res%checkpoint = checkpoint_path(st%checkpoints_written)
    res%cycles_run = cycles_run
    res%loop_seconds = comms_wtime() - loop0
    res%cycles = st%cycle
    res%time = st%t
    res%energy_error = bal%error
    res%wall_seconds = comms_wtime() - wall0
  contains
    !> The owned elements eroded since the last call, to every rank, and
    !> the contact surfaces rebuilt from them (collective).
    subroutine share_erosion(look, settle)
      logical, intent(in) :: look     !< this rank eroded some of its elements
      logical, intent(in) :: settle   !< put slave nodes a hair behind the new faces on them (not at a restart:
                                      !< the checkpoint holds the settled positions)
      integer :: i, n_new
      n_new = 0
      if (look) then
        do i = 1, no
          if (owned_gone(i) .or. dom%el_state(dom%el_owned_list(i)) /= el_eroded) cycle
          owned_gone(i) = .true.
          n_new = n_new + 1
          new_gidx(n_new) = dom%el_gidx(dom%el_owned_list(i))
        end do
      end if
      call comms_allgather_count(n_new, erosion_counts)
      if (sum(erosion_counts) == 0) return
      call comms_allgatherv_int(new_gidx(1:n_new), erosion_counts, all_gidx(1:sum(erosion_counts)))
      call contact_erode(ct, all_gidx(1:sum(erosion_counts)))
      ! a slave node flush against an eroded element can be a hair behind
      ! the face its removal exposed: onto it before the next step
      if (settle) then
        call keep_constrained_positions(dom, x_constrained)
        call contact_settle(ct, dom, pt)
        call restore_constrained_positions(dom, x_constrained)
        if (pt%n > 0) call particles_onto_planes(pt, dom%sym_walls)
      end if
    end subroutine

    !> The stable step fell below dt_warn_ratio of the first one (times a
    !> further 1/10 for each warning already given): say which element sets
    !> it, how distorted it and its nodes are, and what can be done. The
    !> element is the lowest global id with the smallest step (collective).
    subroutine warn_small_step()
      integer :: g, i, e, tag, part
      real(rk) :: j_el, j_lo, j_hi
      character(len=600) :: msg
      ! the stiffest element at the node that sets the step
      g = huge(1)
      if (dt_node > 0 .and. dt_local == st%dt_stable) then
        e = dom%nd_el(dom%nd_el_ptr(dt_node))
        do i = dom%nd_el_ptr(dt_node) + 1, dom%nd_el_ptr(dt_node+1) - 1
          if (dom%el_k(dom%nd_el(i)) > dom%el_k(e)) e = dom%nd_el(i)
        end do
        g = dom%el_gidx(e)
      end if
      g = comms_min_int(g)
      e = findloc(dom%el_gidx, g, dim=1)
      tag = comms_min_int(entry_or_huge(dom%el_id, e))
      part = comms_min_int(entry_or_huge(dom%el_part, e))
      j_el = huge(1.0_rk); j_lo = huge(1.0_rk); j_hi = -huge(1.0_rk)
      if (e > 0) then
        j_el = current_volume(dom, e)/dom%el_vol0(e)
        if (dom%anti_locking) then
          do i = 1, dom%corners
            j_lo = min(j_lo, dom%nd_j(dom%el_conn(e,i)))
            j_hi = max(j_hi, dom%nd_j(dom%el_conn(e,i)))
          end do
        end if
      end if
      j_el = comms_min(j_el); j_lo = comms_min(j_lo); j_hi = comms_max(j_hi)
      do while (st%dt_stable < cfg%run%dt_warn_ratio*st%dt0/10.0_rk**dt_warn_level)
        dt_warn_level = dt_warn_level + 1
      end do
      msg = 'time-step collapse: stable step '//real_text(st%dt_stable, 3)//' s, '// &
        real_text(st%dt_stable/st%dt0, 2)//' of the first ('//real_text(st%dt0, 3)//' s), at cycle '// &
        itoa(st%cycle)//', t = '//real_text(st%t, 5)//' s; set by element '//itoa(tag)//' (part '''// &
        trim(dom%part_name(part))//''') at volume ratio '//fixed(j_el, 4)
      if (dom%anti_locking) msg = trim(msg)//', its nodes'' averaged volume ratios '//fixed(j_lo, 4)//' to '// &
        fixed(j_hi, 4)
      call log_warn(trim(msg)//'. The run goes on (next warning at '// &
        real_text(cfg%run%dt_warn_ratio/10.0_rk**dt_warn_level, 1)//' of the first step). What can be done: '// &
        'doc/user-guide.md, "When the time step collapses"')
    end subroutine

    !> The step the next cycle takes: the stable one (dt_initial on the
    !> first cycle), cut to what is left to t_end (last).
    subroutine next_step(dt_next, last)
      real(rk), intent(out) :: dt_next
      logical, intent(out) :: last
      if (st%cycle == 0 .and. cfg%run%dt_initial > 0.0_rk) then
        dt_next = cfg%run%dt_initial
      else
        dt_next = min(cfg%run%dt_safety*st%dt_stable, cfg%run%dt_max)
      end if
      last = st%t + dt_next >= cfg%run%t_end*(1.0_rk - 1.0e-12_rk)
      if (last) dt_next = cfg%run%t_end - st%t
    end subroutine

    !> Whether a cycle ending at time t (the run's last: last) writes a history row.
    logical function history_due_at(t, last)
      real(rk), intent(in) :: t
      logical, intent(in) :: last
      history_due_at = last .or. t >= st%t_next_hist*(1.0_rk - 1.0e-12_rk)
    end function

    !> Whether cycle number c (the run's last: last) prints a progress line.
    logical function print_due_at(c, last)
      integer, intent(in) :: c
      logical, intent(in) :: last
      print_due_at = mod(c, cfg%run%cycle_print) == 0 .or. last
    end function

    !> Whether the next cycle computes the balance: the balance block's
    !> conditions with the step that cycle takes (the run's end by the
    !> kinetic energy or a stop falls on a balance_interval cycle).
    logical function balance_due_next()
      real(rk) :: dt_next
      logical :: last
      call next_step(dt_next, last)
      last = last .or. st%cycle + 1 >= cfg%run%max_cycles
      balance_due_next = history_due_at(st%t + dt_next, last) .or. print_due_at(st%cycle + 1, last) &
                         .or. mod(st%cycle + 1, balance_interval) == 0
    end function

    !> A history row (rank 0 writes; every rank learns whether it could).
    subroutine history_row(dt)
      real(rk), intent(in) :: dt
      ok = .true.
      errmsg = ''
      if (comms_is_root()) call write_history_row(hist, st%t, st%cycle, dt, bal, row, ok, errmsg)
      call output_check(ok, errmsg)
    end subroutine

    !> After a write every rank may or may not have managed: if any failed,
    !> the way out of output_failed (collective).
    subroutine output_check(ok, msg)
      logical, intent(in) :: ok
      character(len=*), intent(in) :: msg
      if (comms_max_int(merge(0, 1, ok)) /= 0) call output_failed(msg, ok)
    end subroutine

    !> An output file cannot be written (full disk, quota, lost mount): each
    !> rank that failed says why, the status file says so, everything open
    !> is closed (HDF5 must not flush at MPI's exit), exit 3 on every rank.
    !> Collective; ok: this rank's part succeeded.
    subroutine output_failed(msg, ok)
      character(len=*), intent(in) :: msg
      logical, intent(in) :: ok
      character(len=:), allocatable :: full
      full = 'at cycle '//itoa(st%cycle)//', t = '//real_text(st%t, 5)//' s; the checkpoints already written '// &
             'are intact: free space and continue with --restart auto'
      if (.not. ok) call log_error_here(msg)
      call write_status(base, 'failed', 'output could not be written '//full)
      call fw_close(fw)
      call history_close(hist)
      call fatal_all(exit_io, 'output could not be written '//full)
    end subroutine

    !> Next output time after t (several intervals may pass in one step).
    subroutine advance(t_next, interval)
      real(rk), intent(inout) :: t_next
      real(rk), intent(in) :: interval
      if (interval <= 0.0_rk) return
      do while (t_next <= st%t*(1.0_rk + 1.0e-12_rk))
        t_next = t_next + interval
      end do
    end subroutine

    !> Rotating checkpoint slots 1..checkpoint_keep: the newest replaces the oldest.
    function checkpoint_path(n_written) result(path)
      integer, intent(in) :: n_written
      character(len=:), allocatable :: path
      path = base//'_ckpt'//itoa(mod(max(n_written, 1) - 1, cfg%output%checkpoint_keep) + 1)//'.h5'
    end function

    subroutine write_checkpoint()
      real(rk) :: w0
      integer(i8) :: acc(0:exact_limbs, 2)
      w0 = comms_wtime()
      acc(:,1) = walls%work
      acc(:,2) = walls%contact_work
      call comms_sum_exact(acc)
      st%wall_work = acc(:,1)
      st%contact_work = acc(:,2)
      st%checkpoints_written = st%checkpoints_written + 1
      ! a checkpoint is never ahead of the history on disk (the field file
      ! is synced at every step it commits)
      ok = .true.
      errmsg = ''
      if (comms_is_root()) call history_sync(hist, ok, errmsg)
      call output_check(ok, errmsg)
      call checkpoint_write(checkpoint_path(st%checkpoints_written), dom, st, pt, ok, errmsg)
      if (.not. ok) call output_failed(errmsg, .not. comms_is_root())   ! the same verdict everywhere: root says it
      ckpt_seconds = comms_wtime() - w0
      write(line, '(a,i0,a,es12.5,a)') 'checkpoint at cycle ', st%cycle, ', t = ', st%t, ' s: '// &
        checkpoint_path(st%checkpoints_written)//' ('//fixed(ckpt_seconds, 2)//' s)'
      call log_info(line)
    end subroutine

    subroutine open_outputs()
      integer, allocatable :: conn_global(:,:)
      ok = .true.
      errmsg = ''
      if (comms_is_root()) call make_directories(trim(cfg%output%directory), ok, errmsg)
      call fatal_unless_all_ok(exit_io, ok, '&output directory: '//errmsg)
      call status_running()
      ! the field file gets each rank's owned nodes (1..n_owned_nodes) and elements
      work_node = transpose(dom%nd_x0(:,1:dom%n_owned_nodes))
      allocate(conn_global(no,dom%corners))
      do k = 1, dom%corners
        conn_global(:,k) = dom%nd_gidx(dom%el_conn(dom%el_owned_list,k))
      end do
      call fw_open(fw, base//'.h5', base//'.xmf', dom%n_global_nodes, dom%n_global_elems, &
                   dom%nd_gidx(1:dom%n_owned_nodes), dom%el_gidx(dom%el_owned_list), &
                   dom%nd_id(1:dom%n_owned_nodes), dom%el_id(dom%el_owned_list), conn_global, &
                   dom%el_part(dom%el_owned_list), work_node, &
                   cfg%resolved_text, program_version, trim(cfg%run%title), comms_size(), ok, errmsg)
      call output_check(ok, errmsg)
      if (comms_is_root()) call history_open(hist, base//'_history.csv', history_header(dom, ct), &
                                             history_preamble(dom), ok, errmsg)
      call output_check(ok, errmsg)
    end subroutine

    !> Status 'running' before any output is opened, while there is room: a
    !> full disk can then still say 'failed' in it, and a run killed hard
    !> leaves it.
    subroutine status_running()
      call write_status(base, 'running', 'since cycle '//itoa(st%cycle)//'; a run killed hard (out of memory, '// &
        'node failure, kill -9) leaves this: continue with --restart auto')
    end subroutine

    !> Continue the field file and the history of the run the checkpoint
    !> came from, dropping what was written after it.
    subroutine reopen_outputs()
      integer :: bad_out
      call status_running()
      bad_out = 0
      errmsg = ''
      if (comms_is_root()) then
        call history_reopen(hist, base//'_history.csv', history_header(dom, ct), history_preamble(dom), &
                            st%history_rows, st%cycle, ok, errmsg)
        if (.not. ok) bad_out = 1
        if (ok .and. hist%rows < st%history_rows) call log_warn('restart: the history '//base// &
          '_history.csv holds '//itoa(hist%rows)//' rows up to the checkpoint, which was written after row '// &
          itoa(st%history_rows)//': '//itoa(st%history_rows - hist%rows)//' rows were lost (the file was '// &
          'damaged or cut after the checkpoint); the run goes on from the checkpoint')
      end if
      if (comms_max_int(bad_out) /= 0) call fatal_all(exit_io, 'restart: '//errmsg)
      call fw_reopen(fw, base//'.h5', base//'.xmf', dom%n_global_nodes, dom%n_global_elems, &
                     dom%nd_gidx(1:dom%n_owned_nodes), dom%el_gidx(dom%el_owned_list), st%field_steps, &
                     trim(cfg%run%title), ok, errmsg, dom%corners)
      call fatal_unless_all_ok(exit_io, ok, 'restart: '//errmsg)
    end subroutine

    subroutine write_fields(fw, dom, t, cycle, svm, rho)
      type(field_writer_t), intent(inout) :: fw
      type(domain_t), intent(in) :: dom
      real(rk), intent(in) :: t
      integer, intent(in) :: cycle
      real(rk), intent(inout) :: svm(:), rho(:)
      integer :: i, e
      real(rk) :: s6(6)
      logical :: ok
      character(len=:), allocatable :: msg
      do i = 1, size(dom%el_owned_list)
        e = dom%el_owned_list(i)
        s6 = dom%el_s(e,:)
        svm(i) = von_mises(s6)
        ! the density the EOS saw (rho0 / J*), consistent with the pressure
        rho(i) = dom%mat(dom%el_mat(e))%rho0/dom%el_j(e)
      end do
      ! the field file holds (n,3) tables of the owned rows
      work_node = transpose(dom%nd_x(:,1:dom%n_owned_nodes))
      call fw_begin_step(fw, t, cycle, work_node, ok, msg)
      work_node = transpose(dom%nd_v(:,1:dom%n_owned_nodes))
      if (ok) call fw_node_vector(fw, 'velocity', work_node, ok, msg, 'm/s')
      ! for Warp By Vector and readers that take the first step's geometry
      work_node = transpose(dom%nd_x(:,1:dom%n_owned_nodes) - dom%nd_x0(:,1:dom%n_owned_nodes))
      if (ok) call fw_node_vector(fw, 'displacement', work_node, ok, msg, 'm')
      work_elem = dom%el_p(dom%el_owned_list)
      if (ok) call fw_elem_scalar(fw, 'pressure', work_elem, ok, msg, 'Pa')
      if (ok) call fw_elem_scalar(fw, 'von_mises', svm, ok, msg, 'Pa')
      work_elem = dom%el_eps_p(dom%el_owned_list)
      if (ok) call fw_elem_scalar(fw, 'plastic_strain', work_elem, ok, msg, '-')
      work_elem = dom%el_temp(dom%el_owned_list)
      if (ok) call fw_elem_scalar(fw, 'temperature', work_elem, ok, msg, 'K')
      if (ok) call fw_elem_scalar(fw, 'density', rho, ok, msg, 'kg/m3')
      call element_time_steps(dom, work_step)
      work_elem = work_step(dom%el_owned_list)
      if (ok) call fw_elem_scalar(fw, 'time_step', work_elem, ok, msg, 's')
      if (ok .and. fracture_on) then
        work_elem = dom%el_damage(dom%el_owned_list)
        call fw_elem_scalar(fw, 'damage', work_elem, ok, msg, '-')
        work_elem = real(dom%el_state(dom%el_owned_list), rk)
        if (ok) call fw_elem_scalar(fw, 'fracture_state', work_elem, ok, msg, '-')
      end if
      if (ok .and. ct%n_interfaces > 0) then
        call contact_pressure(ct, dom)
        work_node(:,1) = 0
        do i = 1, ct%n_nodes
          if (ct%local(i) > 0 .and. ct%local(i) <= dom%n_owned_nodes) work_node(ct%local(i),1) = ct%pressure(i)
        end do
        call fw_node_scalar(fw, 'contact_pressure', work_node(:,1), ok, msg, 'Pa')
      end if
      if (ok .and. pt%enabled) call write_particles(fw, ok, msg)
      if (ok) call fw_end_step(fw, ok, msg)
      call output_check(ok, msg)
    end subroutine

    !> The rigid walls wl on the particles at this cycle's step: their
    !> work and impulses into the run's sums on the root rank (impulse), into
    !> dummies on the others (every rank has every particle).
    subroutine walls_on_particles(wl, impulse, impulse_dummy)
      type(wall_t), intent(in) :: wl(:)
      integer(i8), intent(inout) :: impulse(0:, :), impulse_dummy(0:, :)
      if (comms_is_root()) then
        call walls_on_points(wl, pt%n, pt%x, pt%v, pt%m, dt, walls%work, impulse)
      else
        call walls_on_points(wl, pt%n, pt%x, pt%v, pt%m, dt, wall_work_dummy, impulse_dummy)
      end if
    end subroutine

    !> The particles' fields into the step being written (every rank has
    !> them; the root writes).
    subroutine write_particles(fw, ok, msg)
      type(field_writer_t), intent(inout) :: fw
      logical, intent(out) :: ok
      character(len=:), allocatable, intent(out) :: msg
      real(rk), allocatable :: values(:,:)
      integer :: q
      allocate(values(pt%n, size(particle_scalars)))
      do q = 1, pt%n
        values(q,:) = [pt%m(q), pt%rho(q), pt%p(q), pt%e(q), pt%temp(q), pt%eps_p(q), real(pt%part(q), rk), &
                       real(pt%elem(q) - 1, rk), von_mises(pt%s(:,q)), merge(1.0_rk, 0.0_rk, pt%strong(q))]
      end do
      call fw_particles(fw, pt%x(:,1:pt%n), pt%v(:,1:pt%n), values, ok, msg)
    end subroutine
  end subroutine

  !> r in scientific notation with d decimals, no blanks.
  pure function real_text(r, d) result(txt)
    real(rk), intent(in) :: r
    integer, intent(in) :: d
    character(len=:), allocatable :: txt
    character(len=32) :: buf, fmt
    write(fmt, '(a,i0,a,i0,a)') '(es', d + 8, '.', d, ')'
    write(buf, fmt) r
    txt = trim(adjustl(buf))
  end function

  !> a(k), or huge when k = 0 (this rank does not hold the entry): the
  !> operand of a global minimum that finds the rank that does.
  pure integer function entry_or_huge(a, k) result(v)
    integer, intent(in) :: a(:), k
    v = huge(1)
    if (k > 0) v = a(k)
  end function

  !> <case>.status, for batch scripts: 'running' (from the first cycle; a
  !> run killed hard leaves it), 'complete', 'checkpointed' (with the
  !> checkpoint to continue from), 'max_cycles' or 'failed' (with why).
  !> Written whole to a temporary name and renamed (rank 0); when that
  !> fails (a full disk), the old file is overwritten in place, which needs
  !> no new space (its first block is already there), the rest blank lines.
  subroutine write_status(base, status, detail)
    character(len=*), intent(in) :: base, status, detail
    character(len=:), allocatable :: text
    integer :: u, ios, old_size, new_size
    if (.not. comms_is_root()) return
    text = 'status = '//status//new_line('a')
    if (len_trim(detail) > 0) text = text//'detail = '//detail(1:min(len_trim(detail), 3000))//new_line('a')
    open(newunit=u, file=base//'.status.tmp', status='replace', access='stream', form='unformatted', &
         action='write', iostat=ios)
    if (ios == 0) write(u, iostat=ios) text
    if (ios == 0) close(u, iostat=ios)
    new_size = -1
    if (ios == 0) inquire(file=base//'.status.tmp', size=new_size)
    ! a full file system may accept the write and the close yet keep nothing
    if (new_size == len(text)) then
      if (rename_file(base//'.status.tmp', base//'.status')) return
    end if
    call remove_if_present(base//'.status.tmp')
    inquire(file=base//'.status', size=old_size)
    if (old_size > len(text)) text = text//repeat(new_line('a'), old_size - len(text))
    open(newunit=u, file=base//'.status', status='old', access='stream', form='unformatted', action='write', &
         iostat=ios)
    if (ios == 0) write(u, pos=1, iostat=ios) text
    close(u, iostat=ios)
  end subroutine

  !> Where a run that lost its energy balance is worst: the element with the
  !> largest specific internal energy and the fastest node (mesh-file ids;
  !> a non-finite value counts as the largest). Collective.
  function hot_spot(dom) result(msg)
    type(domain_t), intent(in) :: dom
    character(len=:), allocatable :: msg
    character(len=200) :: buf
    real(rk), allocatable :: e_abs(:), speed(:)
    integer :: e_tag, n_tag
    real(rk) :: e_val, n_val
    e_abs = abs(dom%el_e)
    where (.not. ieee_is_finite(e_abs)) e_abs = huge(1.0_rk)
    speed = sqrt(dom%nd_v(1,:)**2 + dom%nd_v(2,:)**2 + dom%nd_v(3,:)**2)
    where (.not. ieee_is_finite(speed)) speed = huge(1.0_rk)
    call global_argmax(e_abs, dom%el_gidx, dom%el_id, e_val, e_tag)
    call global_argmax(speed, dom%nd_gidx, dom%nd_id, n_val, n_tag)
    write(buf, '(a,i0,a,es10.3,a,i0,a,es10.3,a)') 'worst element ', e_tag, ' (|specific internal energy| ', &
      e_val, ' J/kg), fastest node ', n_tag, ' (', n_val, ' m/s)'
    msg = trim(buf)
  end function

  !> The largest value over all ranks and the tag of the lowest global
  !> index holding it.
  subroutine global_argmax(values, gidx, tags, vmax, tag)
    real(rk), intent(in) :: values(:)
    integer, intent(in) :: gidx(:), tags(:)
    real(rk), intent(out) :: vmax
    integer, intent(out) :: tag
    integer :: i, g
    vmax = -huge(1.0_rk)
    if (size(values) > 0) vmax = maxval(values)
    vmax = comms_max(vmax)
    g = huge(1)
    do i = 1, size(values)
      if (values(i) == vmax) g = min(g, gidx(i))
    end do
    g = comms_min_int(g)
    i = findloc(gidx, g, dim=1)
    tag = comms_min_int(entry_or_huge(tags, i))
  end subroutine

  !> Whether any material can fracture (history columns, fields, log).
  logical function any_fracture(dom)
    type(domain_t), intent(in) :: dom
    integer :: k
    any_fracture = .false.
    do k = 1, size(dom%mat)
      any_fracture = any_fracture .or. fracture_enabled(dom%mat(k))
    end do
  end function

  !> The history's comment line before its header: what its integrated
  !> columns stand for: a 2D run's (per revolution, per metre) and a model
  !> cut by symmetry planes (the modelled part; for n perpendicular planes
  !> through the body the whole has 2^n times it). '' when neither: no such
  !> line. No comma, so that no reader takes it for the header.
  function history_preamble(dom) result(text)
    type(domain_t), intent(in) :: dom
    character(len=:), allocatable :: text
    integer :: n_sym
    select case (dom%geometry)
    case (geometry_axisymmetric)
      text = 'udar history: axisymmetric (x = r; y the axis): masses; energies; momenta and forces are '// &
             'those of the full revolution (2 pi rad); momentum_x and angular_momentum_* are sums over the '// &
             'meridian section (no momentum of the body)'
    case (geometry_plane_strain)
      text = 'udar history: plane strain: masses; energies; momenta and forces are per metre of depth (z)'
    case default
      text = ''
    end select
    ! (axisymmetric, the last is the axis: no symmetry of the body)
    n_sym = size(dom%sym_walls) - merge(1, 0, dom%geometry == geometry_axisymmetric)
    if (n_sym == 0) return
    if (len(text) == 0) then
      text = 'udar history:'
    else
      text = text//';'
    end if
    text = text//' '//trim(itoa(n_sym))//' symmetry '//trim(merge('plane', 'line ', dom%geometry == geometry_solid))// &
           trim(merge('s', ' ', n_sym > 1))// &
           ': the integrated columns are those of the modelled part (whole body = '// &
           trim(itoa(2**n_sym))//' x model where they are perpendicular and through its middle)'
  end function

  !> Decks with contact get, after the parts, each interface's normal and
  !> friction force and its largest slip velocity left after the pass;
  !> decks with fracture then the fractured and eroded element counts, the
  !> eroded internal energy and the mass (the mesh's and the particles':
  !> erosion and conversion keep it); decks whose eroded elements become
  !> particles then their count, mass, kinetic and internal energy and the
  !> kinetic energy conversion made heat.
  function history_columns(dom, ct) result(cols)
    type(domain_t), intent(in) :: dom
    type(contact_t), intent(in) :: ct
    character(len=80), allocatable :: cols(:)
    integer :: ip, nc
    character(len=80) :: base(n_base) = [character(len=80) :: 'time', 'cycle', 'dt', 'kinetic', 'internal', &
      'plastic_work', 'wall_work', 'total', 'energy_error', 'momentum_x', 'momentum_y', 'momentum_z', 'wall_force', &
      'angular_momentum_x', 'angular_momentum_y', 'angular_momentum_z']
    nc = per_interface*ct%n_interfaces + merge(1, 0, ct%n_interfaces > 0)
    allocate(cols(n_base + per_part*dom%n_parts + nc + merge(4, 0, any_fracture(dom)) + &
                  merge(5, 0, particles_converting(dom)) + gauge_values(dom)))
    if (gauge_values(dom) > 0) cols(size(cols) - gauge_values(dom) + 1:) = gauge_columns(dom)
    if (any_fracture(dom)) cols(n_base + per_part*dom%n_parts + nc + 1:n_base + per_part*dom%n_parts + nc + 4) = &
      [character(len=80) :: 'fractured', 'eroded', 'eroded_energy', 'mass']
    if (particles_converting(dom)) cols(size(cols)-gauge_values(dom)-4:size(cols)-gauge_values(dom)) = &
      [character(len=80) :: 'particles', 'particle_mass', 'particle_kinetic', 'particle_internal', 'conversion_heat']
    cols(1:n_base) = base
    do ip = 1, dom%n_parts
      cols(n_base + per_part*(ip-1) + 1:n_base + per_part*ip) = [character(len=80) :: &
        'ke_'//trim(dom%part_name(ip)), 'com_x_'//trim(dom%part_name(ip)), 'com_y_'//trim(dom%part_name(ip)), &
        'com_z_'//trim(dom%part_name(ip)), 'internal_'//trim(dom%part_name(ip)), &
        'plastic_work_'//trim(dom%part_name(ip)), 'eroded_energy_'//trim(dom%part_name(ip)), &
        'mass_'//trim(dom%part_name(ip)), 'momentum_x_'//trim(dom%part_name(ip)), &
        'momentum_y_'//trim(dom%part_name(ip)), 'momentum_z_'//trim(dom%part_name(ip)), &
        'velocity_x_'//trim(dom%part_name(ip)), 'velocity_y_'//trim(dom%part_name(ip)), &
        'velocity_z_'//trim(dom%part_name(ip))]
    end do
    if (nc == 0) return
    ip = n_base + per_part*dom%n_parts
    do nc = 1, ct%n_interfaces
      cols(ip + per_interface*(nc-1) + 1:ip + per_interface*nc) = [character(len=80) :: &
        'contact_normal_'//trim(ct%ifc(nc)%name), 'contact_friction_'//trim(ct%ifc(nc)%name), &
        'contact_slip_'//trim(ct%ifc(nc)%name), 'contact_deep_'//trim(ct%ifc(nc)%name), &
        'contact_force_x_'//trim(ct%ifc(nc)%name), 'contact_force_y_'//trim(ct%ifc(nc)%name), &
        'contact_force_z_'//trim(ct%ifc(nc)%name)]
    end do
    cols(ip + per_interface*ct%n_interfaces + 1) = 'contact_work'
  end function

  !> The number of history values of the gauges: a node's displacement and
  !> velocity (6), an element's pressure, stress, von Mises stress, plastic
  !> strain, temperature and density (11), a material point's position and
  !> velocity and its element's values (17).
  integer function gauge_values(dom) result(n)
    type(domain_t), intent(in) :: dom
    integer :: g
    n = 0
    if (.not. allocated(dom%gauge_kind)) return
    do g = 1, size(dom%gauge_kind)
      n = n + gauge_width(dom%gauge_kind(g))
    end do
  end function

  pure integer function gauge_width(kind) result(n)
    integer, intent(in) :: kind
    select case (kind)
    case (gauge_node)
      n = 6
    case (gauge_element)
      n = 12
    case default
      n = 18
    end select
  end function

  !> The gauges' history column names, gauge_<name>_<quantity>.
  function gauge_columns(dom) result(cols)
    type(domain_t), intent(in) :: dom
    character(len=80), allocatable :: cols(:)
    character(len=16), parameter :: node_q(6) = [character(len=16) :: 'ux', 'uy', 'uz', 'vx', 'vy', 'vz'], &
      point_q(6) = [character(len=16) :: 'x', 'y', 'z', 'vx', 'vy', 'vz'], &
      elem_q(12) = [character(len=16) :: 'pressure', 'sxx', 'syy', 'szz', 'sxy', 'syz', 'szx', 'von_mises', &
                    'plastic_strain', 'temperature', 'density', 'state']
    character(len=16), allocatable :: q(:)
    integer :: g, k
    allocate(cols(0))
    do g = 1, size(dom%gauge_kind)
      select case (dom%gauge_kind(g))
      case (gauge_node)
        q = node_q
      case (gauge_element)
        q = elem_q
      case default
        q = [point_q, elem_q]
      end select
      cols = [character(len=80) :: cols, ('gauge_'//trim(dom%gauge_name(g))//'_'//trim(q(k)), k = 1, size(q))]
    end do
  end function

  !> This rank's share of the gauges' values into their exact accumulators
  !> (one column each): what it owns, the rest 0, so the global sum is each
  !> value rounded once, the same for any partition. A point's position and
  !> velocity are its element's corners' weighted sums (each corner's owner
  !> adds its term). Once the element has become a particle (eroded =
  !> 'particles') the gauge follows the particle (every rank has it, the
  !> root adds it): its position, velocity and state; an element eroded
  !> into free nodes carries no stress (0), its plastic strain, temperature
  !> and density stay those it had.
  subroutine add_gauges(dom, pt, acc)
    type(domain_t), intent(in) :: dom
    type(particles_t), intent(in) :: pt
    integer(i8), intent(inout) :: acc(0:,:)
    integer :: g, c, a, n, e, k, q
    c = 0
    do g = 1, size(dom%gauge_kind)
      if (dom%gauge_kind(g) == gauge_node) then
        n = dom%gauge_nodes_loc(1,g)
        if (n > 0) then
          do k = 1, 3
            call exact_add(acc(:,c+k), dom%nd_x(k,n) - dom%nd_x0(k,n))
            call exact_add(acc(:,c+3+k), dom%nd_v(k,n))
          end do
        end if
        c = c + 6
        cycle
      end if
      q = 0
      if (pt%n > 0) q = findloc(pt%elem(1:pt%n), dom%gauge_elem(g), dim=1)
      if (dom%gauge_kind(g) == gauge_point) then
        if (q > 0) then
          if (comms_is_root()) then
            do k = 1, 3
              call exact_add(acc(:,c+k), pt%x(k,q))
              call exact_add(acc(:,c+3+k), pt%v(k,q))
            end do
          end if
        else
          do a = 1, 4
            n = dom%gauge_nodes_loc(a,g)
            if (n == 0) cycle
            do k = 1, 3
              call exact_add(acc(:,c+k), dom%gauge_w(a,g)*dom%nd_x(k,n))
              call exact_add(acc(:,c+3+k), dom%gauge_w(a,g)*dom%nd_v(k,n))
            end do
          end do
        end if
        c = c + 6
      end if
      e = dom%gauge_elem_loc(g)
      if (q > 0) then
        if (comms_is_root()) call add_state(pt%p(q), pt%s(:,q), pt%eps_p(q), pt%temp(q), pt%rho(q), gauge_particle)
      else if (e > 0) then
        if (dom%el_state(e) == el_eroded) then
          call add_state(0.0_rk, [(0.0_rk, k = 1, 6)], dom%el_eps_p(e), dom%el_temp(e), &
                         dom%mat(dom%el_mat(e))%rho0/dom%el_j(e), dom%el_state(e))
        else
          call add_state(dom%el_p(e), dom%el_s(e,:), dom%el_eps_p(e), dom%el_temp(e), &
                         dom%mat(dom%el_mat(e))%rho0/dom%el_j(e), dom%el_state(e))
        end if
      end if
      c = c + gauge_width(gauge_element)
    end do
  contains
    !> An element's or a particle's values: pressure p, the Cauchy stress
    !> (the deviator s less p; no viscosity), von Mises, plastic strain,
    !> temperature, density and what it is (gauge state).
    subroutine add_state(p, s6, eps_p, temp, rho, state)
      real(rk), intent(in) :: p, s6(6), eps_p, temp, rho
      integer, intent(in) :: state
      call exact_add(acc(:,c+1), p)
      do k = 1, 3
        call exact_add(acc(:,c+1+k), s6(k) - p)
        call exact_add(acc(:,c+4+k), s6(3+k))
      end do
      call exact_add(acc(:,c+8), von_mises(s6))
      call exact_add(acc(:,c+9), eps_p)
      call exact_add(acc(:,c+10), temp)
      call exact_add(acc(:,c+11), rho)
      call exact_add(acc(:,c+12), real(state, rk))
    end subroutine
  end subroutine

  !> The history's header: each column's name and its SI unit in brackets,
  !> 'kinetic [J]'; a plane-strain run's integrated columns (energies,
  !> momenta, forces, masses) are per metre of depth, 'kinetic [J/m]',
  !> 'momentum_x [(kg m/s)/m]'.
  function history_header(dom, ct) result(cols)
    type(domain_t), intent(in) :: dom
    type(contact_t), intent(in) :: ct
    character(len=96), allocatable :: cols(:)
    character(len=80), allocatable :: names(:)
    character(len=:), allocatable :: unit
    logical :: integrated
    integer :: k
    names = history_columns(dom, ct)
    allocate(cols(size(names)))
    do k = 1, size(names)
      call column_unit(names(k), unit, integrated)
      if (integrated .and. dom%geometry == geometry_plane_strain) then
        if (scan(unit, ' /') > 0) unit = '('//unit//')'
        unit = unit//'/m'
      end if
      cols(k) = trim(names(k))//' ['//unit//']'
    end do
  end function

  !> The unit of history column name, and whether it is integrated over the
  !> body (per metre in plane strain).
  subroutine column_unit(name, unit, integrated)
    character(len=*), intent(in) :: name
    character(len=:), allocatable, intent(out) :: unit
    logical, intent(out) :: integrated
    integrated = .true.
    select case (trim(name))
    case ('time', 'dt')
      unit = 's'
      integrated = .false.
    case ('cycle', 'energy_error', 'fractured', 'eroded', 'particles')
      unit = '-'
      integrated = .false.
    case ('momentum_x', 'momentum_y', 'momentum_z')
      unit = 'kg m/s'
    case ('wall_force')
      unit = 'N'
    case ('angular_momentum_x', 'angular_momentum_y', 'angular_momentum_z')
      unit = 'kg m2/s'
    case ('mass', 'particle_mass')
      unit = 'kg'
    case default
      ! the energies, and the per-part, per-interface and gauge families
      unit = 'J'
      if (starts(name, 'gauge_')) then
        integrated = .false.
        unit = '-'
        if (ends(name, '_vx') .or. ends(name, '_vy') .or. ends(name, '_vz')) then
          unit = 'm/s'
        else if (ends(name, '_ux') .or. ends(name, '_uy') .or. ends(name, '_uz') .or. ends(name, '_x') .or. &
                 ends(name, '_y') .or. ends(name, '_z')) then
          unit = 'm'
        else if (ends(name, '_pressure') .or. ends(name, '_von_mises') .or. ends(name, '_sxx') .or. &
                 ends(name, '_syy') .or. ends(name, '_szz') .or. ends(name, '_sxy') .or. ends(name, '_syz') .or. &
                 ends(name, '_szx')) then
          unit = 'Pa'
        else if (ends(name, '_temperature')) then
          unit = 'K'
        else if (ends(name, '_density')) then
          unit = 'kg/m3'
        end if
      else if (starts(name, 'com_')) then
        unit = 'm'
        integrated = .false.
      else if (starts(name, 'mass_')) then
        unit = 'kg'
      else if (starts(name, 'momentum_')) then
        unit = 'kg m/s'
      else if (starts(name, 'velocity_')) then
        unit = 'm/s'
        integrated = .false.
      else if (starts(name, 'contact_normal_') .or. starts(name, 'contact_friction_') .or. &
               starts(name, 'contact_force_')) then
        unit = 'N'
      else if (starts(name, 'contact_slip_')) then
        unit = 'm/s'
        integrated = .false.
      else if (starts(name, 'contact_deep_')) then
        unit = '-'
        integrated = .false.
      end if
    end select
  contains
    logical function starts(text, head)
      character(len=*), intent(in) :: text, head
      starts = len(text) >= len(head)
      if (starts) starts = text(1:len(head)) == head
    end function

    logical function ends(text, tail)
      character(len=*), intent(in) :: text, tail
      integer :: n
      n = len_trim(text)
      ends = n >= len(tail)
      if (ends) ends = text(n-len(tail)+1:n) == tail
    end function
  end subroutine

  subroutine write_history_row(hist, t, cycle, dt, bal, row, ok, errmsg)
    type(history_t), intent(inout) :: hist
    real(rk), intent(in) :: t, dt
    integer, intent(in) :: cycle
    type(balance_t), intent(in) :: bal
    real(rk), intent(inout) :: row(:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer :: ip, np
    np = size(bal%part_ke)
    row(1:n_base) = [t, real(cycle, rk), dt, bal%kinetic, bal%internal, bal%plastic, bal%wall_work, bal%total, &
                     bal%error, bal%momentum, bal%wall_force, bal%angular_momentum]
    do ip = 1, np
      row(n_base + per_part*(ip-1) + 1:n_base + per_part*ip) = [bal%part_ke(ip), bal%part_com(ip,:), &
        bal%part_internal(ip), bal%part_plastic(ip), bal%part_eroded(ip), bal%part_mass(ip), bal%part_momentum(ip,:), &
        mean_velocity(bal%part_momentum(ip,:), bal%part_mass(ip))]
    end do
    ip = n_base + per_part*np + per_interface*size(bal%contact_normal) + merge(1, 0, size(bal%contact_normal) > 0)
    if (size(row) - size(bal%gauge) > ip) row(ip+1:ip+4) = [real(bal%n_fractured, rk), real(bal%n_eroded, rk), &
                                          bal%eroded_energy, &
                                          sum(bal%part_mass)]
    if (size(row) - size(bal%gauge) > ip + 4) row(ip+5:ip+9) = [real(bal%n_particles, rk), bal%particle_mass, &
                                              bal%particle_kinetic, bal%particle_internal, bal%conversion_heat]
    if (size(bal%gauge) > 0) row(size(row) - size(bal%gauge) + 1:) = bal%gauge
    do ip = 1, size(bal%contact_normal)
      row(n_base + per_part*np + per_interface*(ip-1) + 1:n_base + per_part*np + per_interface*ip) = &
        [bal%contact_normal(ip), bal%contact_friction(ip), bal%contact_slip(ip), bal%contact_deep(ip), &
         bal%contact_force(:,ip)]
    end do
    if (size(bal%contact_normal) > 0) row(n_base + 1 + per_part*np + per_interface*size(bal%contact_normal)) = &
      bal%contact_work
    call history_write(hist, row, ok, errmsg)

  contains

    !> A part's mean velocity: its momentum over its mass (0 without mass).
    pure function mean_velocity(p, m) result(v)
      real(rk), intent(in) :: p(3), m
      real(rk) :: v(3)
      v = 0.0_rk
      if (m > 0.0_rk) v = p/m
    end function
  end subroutine

  !> The energy the balance weighs against the start: the kinetic energy of
  !> the half-step velocities, which belongs to the middle of the step, and
  !> the elements' energy there, the mean of the step's two ends (u_start,
  !> the previous cycle's end, when known; else the end's alone). With the
  !> end's, the balance runs ahead by half the energy the step moves between
  !> kinetic and internal, and swings with it (theory.md 10).
  pure real(rk) function balance_energy(bal, u_start, known)
    type(balance_t), intent(in) :: bal
    real(rk), intent(in) :: u_start
    logical, intent(in) :: known
    balance_energy = bal%kinetic + bal%internal + bal%eroded_energy
    if (known) balance_energy = bal%kinetic + 0.5_rk*(u_start + (bal%internal + bal%eroded_energy))
  end function

  !> Adds this rank's owned elements' energies to exact accumulators, each
  !> part's internal energy of the elements left, plastic work and eroded
  !> elements' energy (acc_part: part_sums columns a part, as
  !> compute_balance lays them out: internal the 6th, plastic the 7th,
  !> eroded the 8th; the plastic work only if with_plastic), and counts the
  !> eroded elements (n_ero) and those fractured or eroded (n_frac).
  subroutine add_element_energies(dom, acc_part, n_ero, n_frac, with_plastic)
    type(domain_t), intent(in) :: dom
    integer(i8), intent(inout) :: acc_part(0:,:)
    integer, intent(out) :: n_ero, n_frac
    logical, intent(in) :: with_plastic
    integer :: i, e, c
    n_frac = 0
    n_ero = 0
    do i = 1, size(dom%el_owned_list)
      e = dom%el_owned_list(i)
      c = part_sums*(dom%el_part(e) - 1)
      if (dom%el_state(e) == el_eroded) then
        call exact_add(acc_part(:,c+8), dom%el_mass(e)*dom%el_e(e))
        n_ero = n_ero + 1
      else
        call exact_add(acc_part(:,c+6), dom%el_mass(e)*dom%el_e(e))
      end if
      if (dom%el_state(e) /= el_intact) n_frac = n_frac + 1
      if (with_plastic) call exact_add(acc_part(:,c+7), dom%el_mass(e)*dom%el_wp(e))
    end do
  end subroutine

  !> The elements' energy, internal and eroded, and the particles' internal
  !> energy (global, the same on every rank and bitwise equal to
  !> compute_balance's internal + eroded_energy: the same parts' sums,
  !> each total rounded from them): what the next cycle's balance needs
  !> from this cycle's end.
  real(rk) function element_energy(dom, pt) result(u)
    type(domain_t), intent(in) :: dom
    type(particles_t), intent(in) :: pt
    real(rk) :: ke, ie, eroded
    call part_energies(dom, pt, .false., ke, ie, eroded)
    u = ie + eroded
  end function

  !> compute_balance's kinetic, internal and eroded energies (and the walls'
  !> and the contact's work) alone, bitwise its values: the same parts' exact
  !> sums, one term a node and one an element instead of eighteen and two.
  !> The checks between records (energy error, end of the event) need no
  !> more. The rest of bal is left as it was.
  subroutine compute_energies(dom, walls, pt, bal)
    type(domain_t), intent(in) :: dom
    type(wall_sums_t), intent(in) :: walls
    type(particles_t), intent(in) :: pt
    type(balance_t), intent(inout) :: bal
    integer(i8) :: acc(0:exact_limbs, 2)
    acc(:,1) = walls%work
    acc(:,2) = walls%contact_work
    call comms_sum_exact(acc)
    bal%wall_work = exact_value(acc(:,1))
    bal%contact_work = exact_value(acc(:,2))
    call part_energies(dom, pt, .true., bal%kinetic, bal%internal, bal%eroded_energy)
    bal%total = bal%kinetic + bal%internal + bal%eroded_energy
  end subroutine

  !> The kinetic energy (if with_kinetic; else 0) of the owned nodes and the
  !> particles, the internal energy of the elements left and the particles,
  !> and the eroded elements' energy, global: each part's exact sum rounded,
  !> the parts' values summed and rounded again, as compute_balance does.
  subroutine part_energies(dom, pt, with_kinetic, kinetic, internal, eroded)
    type(domain_t), intent(in) :: dom
    type(particles_t), intent(in) :: pt
    logical, intent(in) :: with_kinetic
    real(rk), intent(out) :: kinetic, internal, eroded
    integer(i8) :: acc(0:exact_limbs, part_sums*dom%n_parts)
    integer :: n_ero, n_frac, n, k, ip
    acc = 0
    call add_element_energies(dom, acc, n_ero, n_frac, .false.)
    if (with_kinetic) then
      do n = 1, dom%n_owned_nodes
        call exact_add(acc(:,part_sums*(dom%nd_part(n) - 1) + 1), point_kinetic(dom%nd_mass(n), dom%nd_v(:,n)))
      end do
    end if
    ! the particles' (every rank has them all: one adds)
    if (comms_is_root()) then
      do k = 1, pt%n
        if (with_kinetic) call exact_add(acc(:,part_sums*(pt%part(k) - 1) + 1), point_kinetic(pt%m(k), pt%v(:,k)))
        call exact_add(acc(:,part_sums*(pt%part(k) - 1) + 6), pt%m(k)*pt%e(k))
      end do
    end if
    call comms_sum_exact(acc)
    kinetic = exact_sum_of([(exact_value(acc(:,part_sums*(ip - 1) + 1)), ip = 1, dom%n_parts)])
    internal = exact_sum_of([(exact_value(acc(:,part_sums*(ip - 1) + 6)), ip = 1, dom%n_parts)])
    eroded = exact_sum_of([(exact_value(acc(:,part_sums*(ip - 1) + 8)), ip = 1, dom%n_parts)])
  end subroutine

  !> Kinetic energy of a point of mass m moving at v (one expression for
  !> every sum that takes it, so they agree to the bit).
  pure real(rk) function point_kinetic(m, v) result(ke)
    real(rk), intent(in) :: m, v(3)
    ke = 0.5_rk*m*(v(1)**2 + v(2)**2 + v(3)**2)
  end function

  !> Global sums over the owned nodes and elements, exact (udar_exact_sum),
  !> hence the same for any partition. Collective.
  subroutine compute_balance(dom, walls, ct, pt, bal)
    type(domain_t), intent(in) :: dom
    type(wall_sums_t), intent(in) :: walls
    type(contact_t), intent(in) :: ct
    type(particles_t), intent(in) :: pt
    type(balance_t), intent(inout) :: bal
    ! (the totals of the parts' columns are summed from them: no columns of their own)
    integer, parameter :: c_mom = 1, c_work = 4, c_cwork = 5, c_ang = 6, c_mx = 9, c_m = 12, c_pm = 13, c_pk = 14, &
                          c_pi = 15, c_wall = 16
    integer :: n, ip, i, np, nw, c_part, n_frac, n_ero
    real(rk) :: ke, mx(3), p(3), lo(3)
    np = dom%n_parts
    nw = size(dom%walls)
    c_part = c_wall + nw            ! per part: part_sums accumulators
    if (.not. allocated(bal%part_ke)) allocate(bal%part_ke(np), bal%part_com(np,3), bal%part_mass(np), &
                                               bal%part_internal(np), bal%part_plastic(np), bal%part_eroded(np), &
                                               bal%part_momentum(np,3), bal%gauge(gauge_values(dom)), &
                                               bal%acc(0:exact_limbs, c_part + part_sums*np + gauge_values(dom) - 1))
    bal%acc = 0
    do n = 1, dom%n_owned_nodes
      call add_point(dom%nd_mass(n), dom%nd_x(:,n), dom%nd_v(:,n), dom%nd_part(n), ke)
    end do
    ! the particles: every rank has them all, one adds them (to their parts too)
    if (comms_is_root()) then
      do n = 1, pt%n
        call add_point(pt%m(n), pt%x(:,n), pt%v(:,n), pt%part(n), ke)
        call exact_add(bal%acc(:,c_pk), ke)
        call exact_add(bal%acc(:,c_part + part_sums*(pt%part(n) - 1) + 5), pt%m(n)*pt%e(n))
        call exact_add(bal%acc(:,c_pi), pt%m(n)*pt%e(n))
        call exact_add(bal%acc(:,c_pm), pt%m(n))
      end do
    end if
    ! the elements' energies, each part's (its totals are the parts' sums, below)
    call add_element_energies(dom, bal%acc(:, c_part:c_part + part_sums*np - 1), n_ero, n_frac, .true.)
    bal%n_fractured = int(comms_sum_int(int(n_frac, i8)))
    bal%n_eroded = int(comms_sum_int(int(n_ero, i8)))
    bal%acc(:,c_work) = walls%work
    bal%acc(:,c_cwork) = walls%contact_work
    do i = 1, nw
      bal%acc(:,c_wall+i-1) = walls%impulse(:,i)
    end do
    call add_gauges(dom, pt, bal%acc(:, c_part + part_sums*np:))
    call comms_sum_exact(bal%acc)
    do i = 1, size(bal%gauge)
      bal%gauge(i) = exact_value(bal%acc(:, c_part + part_sums*np + i - 1))
    end do
    do i = 1, 3
      bal%momentum(i) = exact_value(bal%acc(:,c_mom+i-1))
      lo(i) = exact_value(bal%acc(:,c_ang+i-1))
      mx(i) = exact_value(bal%acc(:,c_mx+i-1))
    end do
    ! about the centre of mass X = sum m x / M: sum m (x - X) x v = sum m x x v - X x P
    p = bal%momentum
    bal%angular_momentum = lo
    if (exact_value(bal%acc(:,c_m)) > 0.0_rk) bal%angular_momentum = lo - cross(mx, p)/exact_value(bal%acc(:,c_m))
    bal%wall_work = exact_value(bal%acc(:,c_work))
    bal%contact_work = exact_value(bal%acc(:,c_cwork))
    bal%n_particles = pt%n
    bal%particle_mass = exact_value(bal%acc(:,c_pm))
    bal%particle_kinetic = exact_value(bal%acc(:,c_pk))
    bal%particle_internal = exact_value(bal%acc(:,c_pi))
    bal%conversion_heat = pt%heat
    ! the wall corrections are part of the velocity update, so they span dt_v
    bal%wall_force = 0.0_rk
    do i = 1, nw
      bal%wall_force = bal%wall_force + exact_value(bal%acc(:,c_wall+i-1))/walls%dt_v
    end do
    do ip = 1, np
      n = c_part + part_sums*(ip - 1)
      bal%part_ke(ip) = exact_value(bal%acc(:,n))
      bal%part_mass(ip) = exact_value(bal%acc(:,n+4))
      bal%part_internal(ip) = exact_value(bal%acc(:,n+5))
      bal%part_plastic(ip) = exact_value(bal%acc(:,n+6))
      bal%part_eroded(ip) = exact_value(bal%acc(:,n+7))
      bal%part_momentum(ip,:) = [exact_value(bal%acc(:,n+8)), exact_value(bal%acc(:,n+9)), exact_value(bal%acc(:,n+10))]
      do i = 1, 3
        bal%part_com(ip,i) = exact_value(bal%acc(:,n+i))
        if (bal%part_mass(ip) > 0.0_rk) bal%part_com(ip,i) = bal%part_com(ip,i)/bal%part_mass(ip)
      end do
    end do
    ! the totals of what the parts have: the parts' rounded values summed
    ! and rounded once more (at most an ulp from the exact total), so that
    ! the part columns add up to them bitwise (math.fsum; two parts: a + b)
    bal%kinetic = exact_sum_of(bal%part_ke)
    bal%internal = exact_sum_of(bal%part_internal)
    bal%plastic = exact_sum_of(bal%part_plastic)
    bal%eroded_energy = exact_sum_of(bal%part_eroded)
    do i = 1, 3
      bal%momentum(i) = exact_sum_of(bal%part_momentum(:,i))
    end do
    bal%total = bal%kinetic + bal%internal + bal%eroded_energy
    ! the contact pass is replicated: its sums are already the same on every rank
    if (.not. allocated(bal%contact_normal)) allocate(bal%contact_normal(ct%n_interfaces), &
                                                      bal%contact_friction(ct%n_interfaces), bal%contact_slip(ct%n_interfaces), &
                                                      bal%contact_deep(ct%n_interfaces), bal%contact_force(3, ct%n_interfaces))
    do i = 1, ct%n_interfaces
      bal%contact_normal(i) = ct%ifc(i)%normal_impulse/walls%dt_v
      bal%contact_friction(i) = ct%ifc(i)%friction_impulse/walls%dt_v
      bal%contact_slip(i) = ct%ifc(i)%max_slip
      bal%contact_deep(i) = real(ct%ifc(i)%n_deep, rk)
      bal%contact_force(:,i) = ct%ifc(i)%master_impulse/walls%dt_v
    end do
  contains
    !> A point of mass m (a node or a particle) of part ip at x moving at v
    !> into the sums: kinetic energy (ke, also returned), momentum, mass
    !> moments, angular momentum, mass; its part's too.
    subroutine add_point(m, x, v, part, ke)
      real(rk), intent(in) :: m, x(3), v(3)
      integer, intent(in) :: part
      real(rk), intent(out) :: ke
      integer :: c, k
      ke = point_kinetic(m, v)
      c = c_part + part_sums*(part - 1)
      call exact_add(bal%acc(:,c), ke)
      lo = m*cross(x, v)
      do k = 1, 3
        call exact_add(bal%acc(:,c_mom+k-1), m*v(k))
        call exact_add(bal%acc(:,c+7+k), m*v(k))
        call exact_add(bal%acc(:,c+k), m*x(k))
        call exact_add(bal%acc(:,c_mx+k-1), m*x(k))
        call exact_add(bal%acc(:,c_ang+k-1), lo(k))
      end do
      call exact_add(bal%acc(:,c+4), m)
      call exact_add(bal%acc(:,c_m), m)
    end subroutine
  end subroutine
end module udar_run
