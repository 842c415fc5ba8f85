!> Unit test of udar_distribution and the halo exchange, on any number of
!> ranks (run alone and under mpirun -np 3): the elastic-bar mesh of the
!> regression tests, partitioned by METIS, distributed, then checked against
!> the global domain every rank still holds; and the nodal time step the
!> stress pass forms as it goes against the separate pass over the node lists.
!> Args: <tests/unit dir> <work dir>.
program test_distribution_mpi
  use udar_kinds, only: rk, i8, max_path_len
  use udar_comms, only: comms_init, comms_finalize, comms_rank, comms_size, comms_max_int, comms_sum_int, &
      comms_is_root, halo_t, comms_halo_exchange, comms_halo_exchange_scalar
  use udar_config, only: config_t
  use udar_domain, only: domain_t, domain_bytes
  use udar_setup, only: init_state
  use udar_partition, only: partition_elements, partition_stats_t
  use udar_distribution, only: distribute_domain, node_owners
  use udar_strings, only: itoa, r2s
  use udar_element_driver, only: element_volumes, element_update
  use udar_element_shared, only: nodal_stable_dt
  use udar_fracture, only: erode_reasons
  use unit_checks, only: check, check_summary
  use unit_domains, only: elastic_bar_mesh_domain
  implicit none
  type(config_t) :: cfg
  type(domain_t) :: glob, loc
  type(halo_t) :: halo
  type(partition_stats_t) :: stats
  integer, allocatable :: part(:), owner(:), lg(:), gl(:)
  character(len=max_path_len) :: unit_dir
  character(len=:), allocatable :: msg
  logical :: ok, fine
  integer :: np, me, n, e, k, g, n_bad
  real(rk), allocatable :: s(:)
  real(rk) :: dt_fused, dt_pass
  integer :: node_fused, node_pass, bad, bad_avg, n_eroded(erode_reasons)
  logical :: eroded_any

  call comms_init()
  np = comms_size()
  me = comms_rank()
  call get_command_argument(1, unit_dir)
  call elastic_bar_mesh_domain(trim(unit_dir), cfg, glob)
  allocate(part(glob%n_elems), source=0)
  if (np > 1) call partition_elements(glob%n_nodes, glob%el_conn, np, part, stats, ok, msg)
  call distribute_domain(glob, part, me, loc, halo)
  ! what every rank holds at start-up: the mesh, no state (doc/performance.md, Memory)
  call agree('global_mesh_domain_holds_no_state', .not. (allocated(glob%el_s) .or. &
    allocated(glob%el_e) .or. allocated(glob%el_mass) .or. allocated(glob%nd_x) .or. allocated(glob%nd_f) .or. &
    allocated(glob%nd_el_corner) .or. allocated(glob%el_gidx)) .and. allocated(loc%el_conn) .and. &
    .not. allocated(loc%el_s), 'only the mesh arrays before init_state')
  call init_state(loc)
  ! the per-element and per-node table of doc/performance.md: 256 bytes per
  ! element (+4 per owned one), 160 per node (+4 per owned one), plus the small
  ! lists (per block: first, last, the node schedule's pointer, its clock ticks)
  call agree('domain_bytes_as_documented', domain_bytes(loc) == 256_i8*loc%n_elems + 4*size(loc%el_owned_list) + &
    160_i8*loc%n_nodes + 4_i8*loc%n_owned_nodes + 8 + 20*loc%n_blocks + 4*size(loc%fixed_nodes) + &
    28*size(loc%sym_nodes), &
    itoa(int(domain_bytes(loc)))//' bytes on rank '//itoa(me))

  ! the nodal step summed in the stress pass (element_update) is the one of
  ! the separate pass over the node lists (nodal_stable_dt) to the bit, and
  ! names the same node: a velocity field that strains every element
  ! differently, two steps of 10 ns
  do n = 1, loc%n_nodes
    loc%nd_v(:,n) = 50.0_rk*[sin(0.7_rk*loc%nd_gidx(n)), cos(1.3_rk*loc%nd_gidx(n)), sin(2.9_rk*loc%nd_gidx(n))]
  end do
  do k = 1, 2
    loc%nd_x = loc%nd_x + 1.0e-8_rk*loc%nd_v
    call element_volumes(loc)
    call element_update(loc, 1.0e-8_rk, bad, bad_avg, n_eroded, eroded_any, dt_fused, node_fused)
    call nodal_stable_dt(loc, dt_pass, node_pass)
    call agree('nodal_step_in_the_stress_pass_'//itoa(k), dt_fused == dt_pass .and. node_fused == node_pass .and. &
      node_pass > 0, r2s(dt_fused)//' s at node '//itoa(node_fused)//' against '//r2s(dt_pass)//' s at node '// &
      itoa(node_pass)//' on rank '//itoa(me))
  end do

  ! every element and node owned exactly once over the ranks
  call agree('elements_owned_once', comms_sum_int(int(count(loc%el_owned), i8)) == glob%n_elems .and. &
    comms_sum_int(sum(int(loc%el_gidx, i8), mask=loc%el_owned)) == int(glob%n_elems, i8)*(glob%n_elems + 1)/2, &
    itoa(glob%n_elems)//' elements on '//itoa(np)//' ranks')
  allocate(owner(glob%n_nodes))
  call node_owners(glob, part, owner)
  call agree('nodes_owned_once', comms_sum_int(int(loc%n_owned_nodes, i8)) == glob%n_nodes .and. &
    all(owner(loc%nd_gidx(1:loc%n_owned_nodes)) == me) .and. all(owner(loc%nd_gidx(loc%n_owned_nodes+1:)) /= me), &
    'owned nodes first, then ghosts of other ranks')
  call agree('local_numbering_ascending', all(loc%el_gidx(2:) > loc%el_gidx(:loc%n_elems-1)) .and. &
    all(loc%nd_gidx(2:loc%n_owned_nodes) > loc%nd_gidx(:loc%n_owned_nodes-1)), 'global order kept')

  ! an owned node sees all its elements, in the global (assembly) order
  n_bad = 0
  do n = 1, loc%n_owned_nodes
    g = loc%nd_gidx(n)
    lg = loc%el_gidx(loc%nd_el(loc%nd_el_ptr(n):loc%nd_el_ptr(n+1)-1))
    gl = glob%nd_el(glob%nd_el_ptr(g):glob%nd_el_ptr(g+1)-1)
    if (size(lg) /= size(gl)) then
      n_bad = n_bad + 1
    else if (any(lg /= gl)) then
      n_bad = n_bad + 1
    end if
  end do
  call agree('owned_incidence_complete_and_ordered', n_bad == 0, itoa(n_bad)//' incomplete lists on rank '//itoa(me))
  fine = .true.
  do e = 1, loc%n_elems
    do k = 1, 4
      if (loc%nd_gidx(loc%el_conn(e,k)) /= glob%el_conn(loc%el_gidx(e),k)) fine = .false.
    end do
  end do
  call agree('connectivity_maps_to_global', fine, 'local el_conn through nd_gidx equals the global one')

  ! halo: owners' values reach every ghost; ghosts start as garbage
  do n = 1, loc%n_nodes
    if (n <= loc%n_owned_nodes) then
      loc%nd_x(:,n) = [1, 2, 3]*real(loc%nd_gidx(n), rk)
      loc%nd_v(:,n) = -real(loc%nd_gidx(n), rk)
    else
      loc%nd_x(:,n) = -1.0_rk
      loc%nd_v(:,n) = 0.0_rk
    end if
  end do
  call comms_halo_exchange(halo, loc%nd_x, loc%nd_v)
  fine = .true.
  do n = 1, loc%n_nodes
    if (any(loc%nd_x(:,n) /= [1, 2, 3]*real(loc%nd_gidx(n), rk)) .or. any(loc%nd_v(:,n) /= -real(loc%nd_gidx(n), rk))) &
      fine = .false.
  end do
  call agree('halo_vector_exchange', fine, 'x and v of every ghost node are the owner''s')
  allocate(s(loc%n_nodes))
  s = 0.5_rk
  s(1:loc%n_owned_nodes) = real(loc%nd_gidx(1:loc%n_owned_nodes), rk)
  call comms_halo_exchange_scalar(halo, s)
  call agree('halo_scalar_exchange', all(s == real(loc%nd_gidx, rk)), 'one value per node')
  call agree('one_rank_has_no_halo', np > 1 .or. (halo%n_neighbors == 0 .and. loc%n_nodes == glob%n_nodes), &
    itoa(halo%n_neighbors)//' neighbours')
  call comms_finalize()
  call check_summary()

contains

  !> One verdict for all ranks, printed once.
  subroutine agree(name, cond, detail)
    character(len=*), intent(in) :: name, detail
    logical, intent(in) :: cond
    logical :: all_ok
    all_ok = comms_max_int(merge(0, 1, cond)) == 0
    if (comms_is_root() .or. .not. all_ok) call check(name, all_ok, detail)
  end subroutine
end program test_distribution_mpi
