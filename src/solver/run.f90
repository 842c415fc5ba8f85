!> The time loop: explicit central difference in EPIC order (nodes, walls,
!> elements, forces), with output, energy balance and the checks that stop a
!> run that has gone bad (inverted element, NaN, energy blow-up) after
!> leaving a last field dump.
module udar_run
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use udar_kinds, only: rk, max_path_len
  use udar_config, only: config_t
  use udar_domain, only: domain_t
  use udar_comms, only: comms_wtime, comms_size, comms_min
  use udar_fatal, only: fatal, exit_physics, exit_io
  use udar_log, only: log_info
  use udar_element_driver, only: element_volumes, nodal_volumes, element_update, nodal_pressures, &
      element_forces_averaged, assemble_forces, element_stable_dt
  use udar_nodal, only: update_velocities, apply_velocity_conditions, apply_rigid_walls, update_positions
  use udar_strength, only: von_mises
  use udar_history, only: history_t, history_open, history_write, history_close
  use udar_field_output, only: field_writer_t, fw_open, fw_begin_step, fw_node_vector, fw_elem_scalar, &
      fw_end_step, fw_close
  use udar_version, only: program_version
  implicit none
  private
  public :: run_simulation, run_result_t

  !> What a finished run reports back (for the summary and the caller).
  type :: run_result_t
    integer :: cycles = 0
    real(rk) :: time = 0.0_rk, energy_error = 0.0_rk, wall_seconds = 0.0_rk
    real(rk) :: ns_per_element_cycle = 0.0_rk   !< wall time of the cycle loop per element and cycle
    character(len=max_path_len) :: field_file = '', history_file = ''
  end type

  !> Energy and momentum balance at one instant.
  type :: balance_t
    real(rk) :: kinetic = 0, internal = 0, plastic = 0, wall_work = 0, total = 0, error = 0
    real(rk) :: momentum(3) = 0, wall_force = 0
    real(rk), allocatable :: part_ke(:), part_com(:,:), part_mass(:)
  end type

contains

  subroutine run_simulation(cfg, dom, res)
    type(config_t), intent(in) :: cfg
    type(domain_t), intent(inout) :: dom
    type(run_result_t), intent(out) :: res
    type(field_writer_t) :: fw
    type(history_t) :: hist
    type(balance_t) :: bal
    real(rk), allocatable :: work_svm(:), work_rho(:), row(:), work_node(:,:)
    real(rk) :: t, dt, dt_old, dt_stable, dt_v, e0, e_ref, wall_step_work, wall_work, t_next_field, &
                t_next_hist, wall0, elapsed, loop0, last_print_wall, left
    integer :: cycle, bad, last_print_cycle
    logical :: ok, done, history_due, print_due
    integer, parameter :: balance_interval = 10
    character(len=:), allocatable :: errmsg, base
    character(len=256) :: line

    wall0 = comms_wtime()
    allocate(work_svm(dom%n_elems), work_rho(dom%n_elems))
    base = trim(cfg%output%directory)//'/'//trim(cfg%output%case_name)
    res%field_file = base//'.h5'
    res%history_file = base//'_history.csv'
    call execute_command_line('mkdir -p "'//trim(cfg%output%directory)//'"')

    allocate(work_node(dom%n_nodes,3))
    work_node = transpose(dom%nd_x0)
    call fw_open(fw, base//'.h5', base//'.xmf', dom%nd_id, dom%el_id, dom%el_conn, dom%el_part, work_node, &
                 cfg%resolved_text, program_version, trim(cfg%run%title), comms_size(), ok, errmsg)
    if (.not. ok) call fatal(exit_io, errmsg)
    call history_open(hist, base//'_history.csv', history_columns(dom), ok, errmsg)
    if (.not. ok) call fatal(exit_io, errmsg)
    allocate(row(size(history_columns(dom))))

    t = 0.0_rk; cycle = 0; wall_work = 0.0_rk
    call element_stable_dt(dom, dt_stable)
    dt_stable = comms_min(dt_stable)
    dt_old = 0.0_rk
    call compute_balance(dom, wall_work, bal)
    e0 = bal%kinetic + bal%internal
    e_ref = max(abs(e0), tiny(1.0_rk))
    call write_fields(fw, dom, t, cycle, work_svm, work_rho)
    call write_history_row(hist, t, cycle, 0.0_rk, bal, row)
    t_next_field = cfg%output%dt_field
    t_next_hist = cfg%output%dt_history
    write(line, '(a,i0,a,i0,a,es10.3,a)') 'start: ', dom%n_elems, ' elements, ', dom%n_nodes, &
      ' nodes, stable step ', dt_stable, ' s'
    call log_info(line)

    done = .false.
    loop0 = comms_wtime()
    last_print_wall = loop0
    last_print_cycle = 0
    do while (.not. done)
      ! ---- time step: the stable one, or what is left to t_end
      if (cycle == 0 .and. cfg%run%dt_initial > 0.0_rk) then
        dt = cfg%run%dt_initial
      else
        dt = min(cfg%run%dt_safety*dt_stable, cfg%run%dt_max)
      end if
      if (t + dt >= cfg%run%t_end*(1.0_rk - 1.0e-12_rk)) then
        dt = cfg%run%t_end - t
        done = .true.
      end if
      dt_v = 0.5_rk*(dt_old + dt)
      ! ---- nodes: v(n+1/2), conditions, walls, x(n+1)
      call update_velocities(dom, dt_v)
      call apply_velocity_conditions(dom)
      call apply_rigid_walls(dom, dt, dt_v, wall_step_work)
      wall_work = wall_work + wall_step_work
      call update_positions(dom, dt)
      t = t + dt
      cycle = cycle + 1
      dt_old = dt
      ! ---- elements: stress(n+1), forces(n+1)
      if (dom%anti_locking) then
        call element_volumes(dom)
        call nodal_volumes(dom)
      end if
      call element_update(dom, dt, dt_stable, bad)
      if (bad /= 0) then
        call write_fields(fw, dom, t, cycle, work_svm, work_rho)
        call fw_close(fw); call history_close(hist)
        write(line, '(a,i0,a,i0,a,es14.7,a)') 'element ', dom%el_id(bad), ' (part '''// &
          trim(dom%part_name(dom%el_part(bad)))//''') inverted (volume <= 0) at cycle ', &
          cycle, ', time ', t, ' s; last state written to '//trim(res%field_file)
        call fatal(exit_physics, line)
      end if
      dt_stable = comms_min(dt_stable)
      if (dom%anti_locking) then
        call nodal_pressures(dom)
        call element_forces_averaged(dom)
      end if
      call assemble_forces(dom)
      if (cycle >= cfg%run%max_cycles) done = .true.

      ! ---- balance, checks, output
      history_due = done .or. t >= t_next_hist*(1.0_rk - 1.0e-12_rk)
      print_due = mod(cycle, cfg%run%cycle_print) == 0 .or. done
      ! the balance costs a pass over the mesh: every few cycles is enough to catch a blow-up
      if (history_due .or. print_due .or. mod(cycle, balance_interval) == 0) then
        call compute_balance(dom, wall_work, bal)
        bal%error = (bal%total - bal%wall_work - e0)/max(e_ref, bal%kinetic)
      end if
      if (.not. ieee_is_finite(bal%total) .or. abs(bal%error) > cfg%run%energy_error_limit) then
        call write_fields(fw, dom, t, cycle, work_svm, work_rho)
        call fw_close(fw); call history_close(hist)
        write(line, '(a,es10.3,a,i0,a,es14.7,a)') 'energy balance lost (error ', bal%error, ') at cycle ', &
          cycle, ', time ', t, ' s; '//hot_spot(dom)//'; last state written to '//trim(res%field_file)
        call fatal(exit_physics, line)
      end if
      if (history_due) then
        call write_history_row(hist, t, cycle, dt, bal, row)
        do while (t_next_hist <= t*(1.0_rk + 1.0e-12_rk) .and. cfg%output%dt_history > 0.0_rk)
          t_next_hist = t_next_hist + cfg%output%dt_history
        end do
      end if
      if (done .or. (cfg%output%dt_field > 0.0_rk .and. t >= t_next_field*(1.0_rk - 1.0e-12_rk))) then
        call write_fields(fw, dom, t, cycle, work_svm, work_rho)
        do while (t_next_field <= t*(1.0_rk + 1.0e-12_rk) .and. cfg%output%dt_field > 0.0_rk)
          t_next_field = t_next_field + cfg%output%dt_field
        end do
      end if
      if (print_due) then
        ! wall time left at the current step size and the recent cost of a cycle
        ! (the step shrinks as elements distort, so an average over the run says too little)
        elapsed = comms_wtime()
        left = (elapsed - last_print_wall)/max(cycle - last_print_cycle, 1)*max(cfg%run%t_end - t, 0.0_rk)/dt
        last_print_wall = elapsed
        last_print_cycle = cycle
        write(line, '(a,i8,a,es11.4,a,es10.3,a,es10.2,a,f9.1,a)') 'cycle', cycle, '  t ', t, ' s  dt ', dt, &
          ' s  energy error ', bal%error, '  wall left ', left, ' s'
        call log_info(line)
      end if
    end do
    call fw_close(fw)
    call history_close(hist)
    res%cycles = cycle
    res%time = t
    res%energy_error = bal%error
    res%wall_seconds = comms_wtime() - wall0
    res%ns_per_element_cycle = 1.0e9_rk*(comms_wtime() - loop0)/(real(dom%n_elems, rk)*max(cycle, 1))
  contains
    subroutine write_fields(fw, dom, t, cycle, svm, rho)
      type(field_writer_t), intent(inout) :: fw
      type(domain_t), intent(in) :: dom
      real(rk), intent(in) :: t
      integer, intent(in) :: cycle
      real(rk), intent(inout) :: svm(:), rho(:)
      integer :: e
      real(rk) :: s6(6)
      logical :: ok
      character(len=:), allocatable :: msg
      do e = 1, dom%n_elems
        s6 = dom%el_s(e,:)
        svm(e) = von_mises(s6)
        rho(e) = dom%el_mass(e)/dom%el_vol(e)
      end do
      ! the field file holds (n,3) tables
      work_node = transpose(dom%nd_x)
      call fw_begin_step(fw, t, cycle, work_node, ok, msg)
      work_node = transpose(dom%nd_v)
      if (ok) call fw_node_vector(fw, 'velocity', work_node, ok, msg)
      if (ok) call fw_elem_scalar(fw, 'pressure', dom%el_p, ok, msg)
      if (ok) call fw_elem_scalar(fw, 'von_mises', svm, ok, msg)
      if (ok) call fw_elem_scalar(fw, 'plastic_strain', dom%el_eps_p, ok, msg)
      if (ok) call fw_elem_scalar(fw, 'temperature', dom%el_temp, ok, msg)
      if (ok) call fw_elem_scalar(fw, 'density', rho, ok, msg)
      if (ok) call fw_end_step(fw, ok, msg)
      if (.not. ok) call fatal(exit_io, msg)
    end subroutine
  end subroutine

  !> Where a run that lost its energy balance is worst: the element with the
  !> largest specific internal energy and the fastest node (mesh-file ids).
  function hot_spot(dom) result(msg)
    type(domain_t), intent(in) :: dom
    character(len=:), allocatable :: msg
    character(len=200) :: buf
    integer :: e, n
    e = maxloc(abs(dom%el_e), dim=1, mask=ieee_is_finite(dom%el_e))
    if (e == 0) e = 1
    n = 1
    do n = 1, dom%n_nodes
      if (.not. ieee_is_finite(dom%nd_v(1,n) + dom%nd_v(2,n) + dom%nd_v(3,n))) exit
    end do
    if (n > dom%n_nodes) n = maxloc(dom%nd_v(1,:)**2 + dom%nd_v(2,:)**2 + dom%nd_v(3,:)**2, dim=1)
    write(buf, '(a,i0,a,es10.3,a,i0,a,es10.3,a)') 'worst element ', dom%el_id(e), ' (specific internal energy ', &
      dom%el_e(e), ' J/kg, part '''//trim(dom%part_name(dom%el_part(e)))//'''), fastest node ', dom%nd_id(n), &
      ' (', norm2(dom%nd_v(:,n)), ' m/s)'
    msg = trim(buf)
  end function

  function history_columns(dom) result(cols)
    type(domain_t), intent(in) :: dom
    character(len=80), allocatable :: cols(:)
    integer :: ip
    character(len=80) :: base(13) = [character(len=80) :: 'time', 'cycle', 'dt', 'kinetic', 'internal', &
      'plastic_work', 'wall_work', 'total', 'energy_error', 'momentum_x', 'momentum_y', 'momentum_z', 'wall_force']
    allocate(cols(13 + 4*dom%n_parts))
    cols(1:13) = base
    do ip = 1, dom%n_parts
      cols(13 + 4*ip - 3) = 'ke_'//trim(dom%part_name(ip))
      cols(13 + 4*ip - 2) = 'com_x_'//trim(dom%part_name(ip))
      cols(13 + 4*ip - 1) = 'com_y_'//trim(dom%part_name(ip))
      cols(13 + 4*ip) = 'com_z_'//trim(dom%part_name(ip))
    end do
  end function

  subroutine write_history_row(hist, t, cycle, dt, bal, row)
    type(history_t), intent(inout) :: hist
    real(rk), intent(in) :: t, dt
    integer, intent(in) :: cycle
    type(balance_t), intent(in) :: bal
    real(rk), intent(inout) :: row(:)
    integer :: ip, np
    np = size(bal%part_ke)
    row(1:13) = [t, real(cycle, rk), dt, bal%kinetic, bal%internal, bal%plastic, bal%wall_work, bal%total, &
                 bal%error, bal%momentum, bal%wall_force]
    do ip = 1, np
      row(13 + 4*ip - 3) = bal%part_ke(ip)
      row(13 + 4*ip - 2:13 + 4*ip) = bal%part_com(ip,:)
    end do
    call history_write(hist, row)
  end subroutine

  !> Sums in ascending node / element id (fixed order).
  subroutine compute_balance(dom, wall_work, bal)
    type(domain_t), intent(in) :: dom
    real(rk), intent(in) :: wall_work
    type(balance_t), intent(inout) :: bal
    integer :: n, e, ip
    real(rk) :: ke
    if (.not. allocated(bal%part_ke)) allocate(bal%part_ke(dom%n_parts), bal%part_com(dom%n_parts,3), &
                                               bal%part_mass(dom%n_parts))
    bal%kinetic = 0; bal%internal = 0; bal%plastic = 0; bal%momentum = 0
    bal%part_ke = 0; bal%part_com = 0; bal%part_mass = 0
    do n = 1, dom%n_nodes
      ke = 0.5_rk*dom%nd_mass(n)*(dom%nd_v(1,n)**2 + dom%nd_v(2,n)**2 + dom%nd_v(3,n)**2)
      bal%kinetic = bal%kinetic + ke
      bal%momentum = bal%momentum + dom%nd_mass(n)*dom%nd_v(:,n)
      ip = dom%nd_part(n)
      bal%part_ke(ip) = bal%part_ke(ip) + ke
      bal%part_com(ip,:) = bal%part_com(ip,:) + dom%nd_mass(n)*dom%nd_x(:,n)
      bal%part_mass(ip) = bal%part_mass(ip) + dom%nd_mass(n)
    end do
    do ip = 1, dom%n_parts
      if (bal%part_mass(ip) > 0.0_rk) bal%part_com(ip,:) = bal%part_com(ip,:)/bal%part_mass(ip)
    end do
    do e = 1, dom%n_elems
      bal%internal = bal%internal + dom%el_mass(e)*dom%el_e(e)
      bal%plastic = bal%plastic + dom%el_mass(e)*dom%el_wp(e)
    end do
    bal%wall_work = wall_work
    bal%total = bal%kinetic + bal%internal
    bal%wall_force = 0.0_rk
    if (allocated(dom%walls)) bal%wall_force = sum(dom%walls%force)
  end subroutine
end module udar_run
