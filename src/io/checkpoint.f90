!> Checkpoints: the whole state of a run in global numbering, so a run can
!> resume on any number of ranks and continue bitwise as if never stopped.
!>
!> One HDF5 file, written collectively with MPI-IO (each rank its owned
!> rows) to NAME.tmp and renamed to NAME when complete, so a checkpoint on
!> disk is always whole. Layout (C order, as h5py shows it):
!>   @format 'udar-checkpoint-5', @version, @n_nodes, @n_elems, the scalars of
!>   run_state_t (@t, @cycle, ...);  hashes int64 (2): model, mesh;
!>   wall_work, contact_work int64 (67): exact work accumulators;  /provenance @n_ranks;
!>   nodes/{x,v,f} (n_nodes,3), nodes/vref (n_nodes); elems/h (the altitudes the contact bounds its returns by);  elems/{vol,j,e,wp,p,q,eps_p,temp,hard,soft}
!>   (n_elems), elems/s (n_elems,6);  with particles (eroded = 'particles'):
!>   @n_particles and particles (n_particles+1, particle_width): row 1 the
!>   heat made at conversion and the count, then one row per particle;
!>   checksum int64 (1).
!> Reading: every rank reads the global arrays and keeps its local entries.
!> The checksum covers every number the restart uses: the scalars, the
!> small datasets and every row (dataset name, global index, values) of the
!> big ones, rows combined by exclusive or so each rank hashes its own rows
!> in any order; a checkpoint whose content does not match it is refused.
module udar_checkpoint
  use, intrinsic :: iso_c_binding, only: c_ptr, c_loc
  use hdf5
  use udar_kinds, only: rk, i8
  use udar_domain, only: domain_t
  use udar_run_state, only: run_state_t
  use udar_particle_model, only: particles_t, particles_reserve
  use udar_exact_sum, only: exact_limbs
  use udar_hash, only: fnv_offset, hash_text, hash_ints, hash_i8s, hash_reals
  use udar_comms, only: comms_world_handle, comms_info_null_handle, comms_is_root, comms_size, comms_max_int, &
      comms_barrier, comms_xor_i8
  use udar_files, only: rename_file, remove_if_present
  use udar_version, only: program_version
  use udar_strings, only: itoa
  implicit none
  private
  public :: checkpoint_write, checkpoint_read, checkpoint_latest, checkpoint_model_hash, checkpoint_mesh_hash

  character(len=*), parameter :: ckpt_format = 'udar-checkpoint-5'
  character(len=*), parameter :: real_names(10) = [character(len=20) :: 't', 'dt_old', 'dt_stable', 'e0', 'e_ref', &
      't_next_field', 't_next_hist', 't_next_checkpoint', 'dt0', 'ke_peak']
  !> checkpoints_written (how the run got here, not its state) lives in /provenance
  character(len=*), parameter :: int_names(6) = [character(len=30) :: 'cycle', 'field_steps', &
      'provenance/checkpoints_written', 'n_nodes', 'n_elems', 'history_rows']
  character(len=*), parameter :: elem_names(14) = [character(len=8) :: 'vol', 'j', 'e', 'wp', 'p', 'q', 'eps_p', &
      'temp', 'hard', 'soft', 'state', 'damage', 'eps_tot', 'h']

  !> a particle's row: x(3), v(3), m, rho, e, p, c, h, temp, eps_p, material, part, element,
  !> deviatoric stress (6), hardening, thermal factor, damage, strength kept (1) or not (0)
  integer, parameter :: particle_width = 27

  type :: ckpt_file_t
    integer(hid_t) :: id = -1, dxpl = -1
    character(len=:), allocatable :: path
    logical :: ok = .true.
    character(len=:), allocatable :: errmsg
    integer(i8) :: rows_hash = 0      !< exclusive or of the row hashes this rank wrote or read
  end type

contains

  ! ------------------------------------------------------------------ hashes

  !> Hash of the physics in the resolved deck: every group but &run, &mesh
  !> (the mesh is hashed by its content) and &output, which may change
  !> between a run and its restart (t_end, wall_limit, output intervals,
  !> where the mesh file lives). Comments and annotations are left out.
  pure integer(i8) function checkpoint_model_hash(resolved) result(h)
    character(len=*), intent(in) :: resolved
    integer :: i, j, q
    logical :: skip, quoted
    character(len=:), allocatable :: line
    h = fnv_offset
    skip = .false.
    i = 1
    do while (i <= len(resolved))
      j = index(resolved(i:), new_line('a'))
      if (j == 0) then
        j = len(resolved) + 1
      else
        j = i + j - 1
      end if
      line = resolved(i:j-1)
      i = j + 1
      ! cut a trailing comment (a '!' outside quotes)
      quoted = .false.
      do q = 1, len(line)
        if (line(q:q) == "'") quoted = .not. quoted
        if (line(q:q) == '!' .and. .not. quoted) then
          line = line(1:q-1)
          exit
        end if
      end do
      line = trim(adjustl(line))
      if (len(line) == 0) cycle
      if (line(1:1) == '&') skip = line == '&run' .or. line == '&mesh' .or. line == '&output'
      if (.not. skip) h = hash_text(h, line//new_line('a'))
    end do
  end function

  !> Hash of the mesh as the run numbers it: initial coordinates, element
  !> nodes, parts and materials, and the mesh-file tags (global domain).
  pure integer(i8) function checkpoint_mesh_hash(glob) result(h)
    type(domain_t), intent(in) :: glob
    integer :: k
    h = fnv_offset
    do k = 1, 3
      h = hash_reals(h, glob%nd_x0(k,:))
    end do
    do k = 1, size(glob%el_conn, 2)
      h = hash_ints(h, glob%el_conn(:,k))
    end do
    h = hash_ints(h, glob%el_part)
    h = hash_ints(h, glob%el_mat)
    h = hash_ints(h, glob%nd_id)
    h = hash_ints(h, glob%el_id)
  end function

  ! ------------------------------------------------------------------- write

  !> Collective. Owned rows of every rank, in global numbering; st%wall_work
  !> must already hold the global sum.
  subroutine checkpoint_write(path, dom, st, pt, ok, errmsg)
    character(len=*), intent(in) :: path
    type(domain_t), intent(in) :: dom
    type(run_state_t), intent(in) :: st
    type(particles_t), intent(in) :: pt
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    type(ckpt_file_t) :: f
    integer(hsize_t), allocatable :: node_first(:), node_count(:), elem_first(:), elem_count(:)
    real(rk), allocatable :: buf(:,:)
    real(rk) :: reals(size(real_names))
    integer :: ints(size(int_names)), k, no, bad
    integer(i8), target :: hashes(2), wall(0:exact_limbs)
    integer(hid_t) :: gid
    integer :: err

    call open_file(f, path//'.tmp', .true.)
    no = size(dom%el_owned_list)
    call runs(dom%nd_gidx(1:dom%n_owned_nodes), node_first, node_count)
    call runs(dom%el_gidx(dom%el_owned_list), elem_first, elem_count)
    if (f%ok) then
      call attr_text(f, 'format', ckpt_format)
      call attr_text(f, 'version', program_version)
      reals = [st%t, st%dt_old, st%dt_stable, st%e0, st%e_ref, st%t_next_field, st%t_next_hist, st%t_next_checkpoint, &
               st%dt0, st%ke_peak]
      ints = [st%cycle, st%field_steps, st%checkpoints_written, dom%n_global_nodes, dom%n_global_elems, &
              st%history_rows]
      do k = 1, size(real_names)
        call attr_real(f, f%id, trim(real_names(k)), reals(k))
      end do
      call h5gcreate_f(f%id, 'provenance', gid, err)
      if (err >= 0) then
        call attr_int(f, gid, 'n_ranks', comms_size())
        call attr_int(f, gid, 'checkpoints_written', ints(3))
        call h5gclose_f(gid, err)
      end if
      do k = 1, size(int_names)
        if (k /= 3) call attr_int(f, f%id, trim(int_names(k)), ints(k))
      end do
      hashes = [st%model_hash, st%mesh_hash]
      wall = st%wall_work
      call write_small_i8(f, 'hashes', hashes)
      call write_small_i8(f, 'wall_work', wall)
      wall = st%contact_work
      call write_small_i8(f, 'contact_work', wall)
      call h5gcreate_f(f%id, 'nodes', gid, err); call h5gclose_f(gid, err)
      call h5gcreate_f(f%id, 'elems', gid, err); call h5gclose_f(gid, err)
      associate (ng => dom%nd_gidx(1:dom%n_owned_nodes))
        call write_rows(f, 'nodes/x', dom%n_global_nodes, 3, node_first, node_count, ng, dom%nd_x(:,1:dom%n_owned_nodes))
        call write_rows(f, 'nodes/v', dom%n_global_nodes, 3, node_first, node_count, ng, dom%nd_v(:,1:dom%n_owned_nodes))
        call write_rows(f, 'nodes/f', dom%n_global_nodes, 3, node_first, node_count, ng, dom%nd_f(:,1:dom%n_owned_nodes))
        call write_rows(f, 'nodes/vref', dom%n_global_nodes, 0, node_first, node_count, ng, &
                        reshape(dom%nd_vref(1:dom%n_owned_nodes), [1, dom%n_owned_nodes]))
      end associate
      allocate(buf(1, no))
      do k = 1, size(elem_names)
        select case (k)
        case (1); buf(1,:) = dom%el_vol(dom%el_owned_list)
        case (2); buf(1,:) = dom%el_j(dom%el_owned_list)
        case (3); buf(1,:) = dom%el_e(dom%el_owned_list)
        case (4); buf(1,:) = dom%el_wp(dom%el_owned_list)
        case (5); buf(1,:) = dom%el_p(dom%el_owned_list)
        case (6); buf(1,:) = dom%el_q(dom%el_owned_list)
        case (7); buf(1,:) = dom%el_eps_p(dom%el_owned_list)
        case (8); buf(1,:) = dom%el_temp(dom%el_owned_list)
        case (9); buf(1,:) = dom%el_hard(dom%el_owned_list)
        case (10); buf(1,:) = dom%el_soft(dom%el_owned_list)
        case (11); buf(1,:) = real(dom%el_state(dom%el_owned_list), rk)
        case (12); buf(1,:) = dom%el_damage(dom%el_owned_list)
        case (13); buf(1,:) = dom%el_eps_tot(dom%el_owned_list)
        case (14); buf(1,:) = dom%el_h(dom%el_owned_list)
        end select
        call write_rows(f, 'elems/'//trim(elem_names(k)), dom%n_global_elems, 0, elem_first, elem_count, &
                        dom%el_gidx(dom%el_owned_list), buf)
      end do
      deallocate(buf)
      allocate(buf(6, no))
      buf = transpose(dom%el_s(dom%el_owned_list,:))
      call write_rows(f, 'elems/s', dom%n_global_elems, 6, elem_first, elem_count, &
                      dom%el_gidx(dom%el_owned_list), buf)
      ! the particles: every rank has them all, the root writes them
      if (pt%enabled) call write_particles()
      hashes(1) = ieor(scalars_hash(reals, ints, [st%model_hash, st%mesh_hash], st%wall_work, st%contact_work), &
                       comms_xor_i8(f%rows_hash))
      call write_small_i8(f, 'checksum', hashes(1:1))
    end if
    call close_file(f)
    ! every rank must have succeeded before the checkpoint replaces the old one
    bad = comms_max_int(merge(0, 1, f%ok))
    ok = bad == 0
    errmsg = ''
    if (comms_is_root()) then
      if (ok) then
        if (.not. rename_file(path//'.tmp', path)) then
          ok = .false.
          errmsg = 'checkpoint: cannot rename '//path//'.tmp to '//path
        end if
      else
        call remove_if_present(path//'.tmp')   ! the previous checkpoints stay
      end if
    end if
    ok = comms_max_int(merge(0, 1, ok)) == 0
    if (.not. ok .and. len(errmsg) == 0) then
      errmsg = 'checkpoint: writing '//path//' failed'
      if (.not. f%ok) errmsg = errmsg//': '//f%errmsg
    end if
    call comms_barrier()
  contains
    subroutine write_particles()
      integer(hsize_t), allocatable :: p_first(:), p_count(:)
      integer, allocatable :: p_gidx(:)
      integer :: q
      call attr_int(f, f%id, 'n_particles', pt%n)
      deallocate(buf)
      if (comms_is_root()) then
        allocate(buf(particle_width, pt%n + 1), p_gidx(pt%n + 1))
        p_gidx = [(q, q = 1, pt%n + 1)]
        buf = 0
        buf(1:2,1) = [pt%heat, real(pt%n, rk)]
        do q = 1, pt%n
          buf(:,q+1) = [pt%x(:,q), pt%v(:,q), pt%m(q), pt%rho(q), pt%e(q), pt%p(q), pt%c(q), pt%h(q), pt%temp(q), &
                        pt%eps_p(q), real(pt%mat(q), rk), real(pt%part(q), rk), real(pt%elem(q), rk), pt%s(:,q), &
                        pt%hard(q), pt%soft(q), pt%damage(q), merge(1.0_rk, 0.0_rk, pt%strong(q))]
        end do
      else
        allocate(buf(particle_width, 0), p_gidx(0))
      end if
      call runs(p_gidx, p_first, p_count)
      call write_rows(f, 'particles', pt%n + 1, particle_width, p_first, p_count, p_gidx, buf)
    end subroutine
  end subroutine

  ! -------------------------------------------------------------------- read

  !> Collective. Fills st (hashes included, for the caller to compare) and
  !> the state of every local node and element from a checkpoint.
  subroutine checkpoint_read(path, dom, st, pt, ok, errmsg)
    character(len=*), intent(in) :: path
    type(domain_t), intent(inout) :: dom
    type(run_state_t), intent(inout) :: st
    type(particles_t), intent(inout) :: pt   !< read if pt%enabled (the deck converts)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    type(ckpt_file_t) :: f
    real(rk), allocatable :: a(:,:)
    real(rk) :: reals(size(real_names))
    integer :: ints(size(int_names)), k
    integer(i8), target :: hashes(2), wall(0:exact_limbs), stored_sum(1)
    character(len=:), allocatable :: fmt

    ok = .false.
    inquire(file=path, exist=ok)
    if (.not. ok) then
      errmsg = 'checkpoint '//path//' does not exist'
      return
    end if
    call open_file(f, path, .false.)
    if (f%ok) then
      call read_attr_text(f, 'format', fmt)
      if (f%ok .and. fmt /= ckpt_format) call fail(f, 'format '''//fmt//''' is not this version''s '''// &
        ckpt_format//''' (a checkpoint of another udar version, or not a udar checkpoint)')
    end if
    do k = 1, size(real_names)
      if (f%ok) call read_attr_real(f, trim(real_names(k)), reals(k))
    end do
    do k = 1, size(int_names)
      if (f%ok) call read_attr_int(f, trim(int_names(k)), ints(k))
    end do
    if (f%ok) then
      if (ints(4) /= dom%n_global_nodes .or. ints(5) /= dom%n_global_elems) call fail(f, &
        'it holds '//itoa(ints(4))//' nodes and '//itoa(ints(5))//' elements, the mesh '// &
        itoa(dom%n_global_nodes)//' and '//itoa(dom%n_global_elems))
    end if
    if (f%ok) call read_small_i8(f, 'hashes', hashes)
    if (f%ok) call read_small_i8(f, 'wall_work', wall)
    if (f%ok) st%wall_work = wall
    if (f%ok) call read_small_i8(f, 'contact_work', wall)
    if (f%ok) st%contact_work = wall
    if (f%ok) call read_small_i8(f, 'checksum', stored_sum)
    if (f%ok) then
      st%history_rows = ints(6)
      st%t = reals(1); st%dt_old = reals(2); st%dt_stable = reals(3); st%e0 = reals(4); st%e_ref = reals(5)
      st%t_next_field = reals(6); st%t_next_hist = reals(7); st%t_next_checkpoint = reals(8); st%dt0 = reals(9)
      st%ke_peak = reals(10)
      st%cycle = ints(1); st%field_steps = ints(2); st%checkpoints_written = ints(3)
      st%model_hash = hashes(1); st%mesh_hash = hashes(2)
    end if
    ! nodes: all local ones, ghosts included
    allocate(a(3, dom%n_global_nodes))
    if (f%ok) call read_all(f, 'nodes/x', a)
    if (f%ok) dom%nd_x = a(:,dom%nd_gidx)
    if (f%ok) call read_all(f, 'nodes/v', a)
    if (f%ok) dom%nd_v = a(:,dom%nd_gidx)
    if (f%ok) call read_all(f, 'nodes/f', a)
    if (f%ok) dom%nd_f = a(:,dom%nd_gidx)
    deallocate(a)
    allocate(a(1, dom%n_global_nodes))
    if (f%ok) call read_all(f, 'nodes/vref', a)
    if (f%ok) dom%nd_vref = a(1,dom%nd_gidx)
    deallocate(a)
    allocate(a(1, dom%n_global_elems))
    do k = 1, size(elem_names)
      if (.not. f%ok) exit
      call read_all(f, 'elems/'//trim(elem_names(k)), a)
      if (.not. f%ok) exit
      select case (k)
      case (1); dom%el_vol = a(1,dom%el_gidx)
      case (2); dom%el_j = a(1,dom%el_gidx)
      case (3); dom%el_e = a(1,dom%el_gidx)
      case (4); dom%el_wp = a(1,dom%el_gidx)
      case (5); dom%el_p = a(1,dom%el_gidx)
      case (6); dom%el_q = a(1,dom%el_gidx)
      case (7); dom%el_eps_p = a(1,dom%el_gidx)
      case (8); dom%el_temp = a(1,dom%el_gidx)
      case (9); dom%el_hard = a(1,dom%el_gidx)
      case (10); dom%el_soft = a(1,dom%el_gidx)
      case (11); dom%el_state = nint(a(1,dom%el_gidx))
      case (12); dom%el_damage = a(1,dom%el_gidx)
      case (13); dom%el_eps_tot = a(1,dom%el_gidx)
      case (14); dom%el_h = a(1,dom%el_gidx)
      end select
    end do
    deallocate(a)
    allocate(a(6, dom%n_global_elems))
    if (f%ok) call read_all(f, 'elems/s', a)
    if (f%ok) dom%el_s = transpose(a(:,dom%el_gidx))
    if (f%ok .and. pt%enabled) call read_particles()
    if (f%ok) then
      if (ieor(scalars_hash(reals, ints, hashes, st%wall_work, st%contact_work), f%rows_hash) /= stored_sum(1)) &
        call fail(f, 'it is damaged: its content does not match the checksum written with it (bytes changed '// &
                  'on disk or in transfer); refused')
    end if
    call close_file(f)
    ok = comms_max_int(merge(0, 1, f%ok)) == 0
    errmsg = ''
    if (.not. ok) then
      if (f%ok) then
        errmsg = 'checkpoint '//path//' could not be read on every rank'
      else
        errmsg = 'checkpoint '//path//': '//f%errmsg
      end if
    end if
  contains
    subroutine read_particles()
      integer :: q, n
      call read_attr_int(f, 'n_particles', n)
      if (.not. f%ok) then
        call fail(f, 'it holds no particles, but this deck''s eroded elements become particles (a checkpoint '// &
                  'of a run with eroded = ''free_nodes''?)')
        return
      end if
      deallocate(a)
      allocate(a(particle_width, n + 1))
      call read_all(f, 'particles', a)
      if (.not. f%ok) return
      if (nint(a(2,1)) /= n) then
        call fail(f, 'its particle count does not match its particles')
        return
      end if
      call particles_reserve(pt, max(n, 1))
      pt%n = n
      pt%heat = a(1,1)
      do q = 1, n
        pt%x(:,q) = a(1:3,q+1)
        pt%v(:,q) = a(4:6,q+1)
        pt%m(q) = a(7,q+1); pt%rho(q) = a(8,q+1); pt%e(q) = a(9,q+1); pt%p(q) = a(10,q+1); pt%c(q) = a(11,q+1)
        pt%h(q) = a(12,q+1); pt%temp(q) = a(13,q+1); pt%eps_p(q) = a(14,q+1)
        pt%mat(q) = nint(a(15,q+1)); pt%part(q) = nint(a(16,q+1)); pt%elem(q) = nint(a(17,q+1))
        pt%s(:,q) = a(18:23,q+1); pt%hard(q) = a(24,q+1); pt%soft(q) = a(25,q+1); pt%damage(q) = a(26,q+1)
        pt%strong(q) = a(27,q+1) /= 0.0_rk
      end do
    end subroutine
  end subroutine

  !> The newest readable checkpoint among BASE_ckpt1.h5 .. BASE_ckptK.h5
  !> (largest cycle), or '' if there is none. Every rank looks (collective).
  function checkpoint_latest(base, keep) result(path)
    character(len=*), intent(in) :: base
    integer, intent(in) :: keep
    character(len=:), allocatable :: path
    type(ckpt_file_t) :: f
    character(len=:), allocatable :: candidate, fmt
    integer :: k, cycle, best
    logical :: exists
    path = ''
    best = -1
    do k = 1, keep
      candidate = base//'_ckpt'//itoa(k)//'.h5'
      inquire(file=candidate, exist=exists)
      if (comms_max_int(merge(1, 0, exists)) == 0) cycle
      call open_file(f, candidate, .false.)
      if (f%ok) call read_attr_text(f, 'format', fmt)
      if (f%ok) then
        if (fmt /= ckpt_format) f%ok = .false.
      end if
      if (f%ok) call read_attr_int(f, 'cycle', cycle)
      call close_file(f)
      if (comms_max_int(merge(0, 1, f%ok)) /= 0) cycle
      if (cycle > best) then
        best = cycle
        path = candidate
      end if
      f = ckpt_file_t()
    end do
  end function

  ! ----------------------------------------------------------------- helpers

  subroutine fail(f, msg)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: msg
    if (.not. f%ok) return
    f%ok = .false.
    f%errmsg = msg
  end subroutine

  !> Collective create (truncate) or read-only open with the MPI-IO driver.
  subroutine open_file(f, path, create)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: path
    logical, intent(in) :: create
    integer(hid_t) :: fapl
    integer :: err, e2
    f%path = path
    f%ok = .true.
    f%errmsg = ''
    call h5open_f(err)
    call h5eset_auto_f(0, err)
    call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, err)
    call h5pset_fapl_mpio_f(fapl, comms_world_handle(), comms_info_null_handle(), err)
    if (create) then
      call h5fcreate_f(path, H5F_ACC_TRUNC_F, f%id, err, access_prp=fapl)
      if (err < 0) call fail(f, 'cannot create the file')
    else
      call h5fopen_f(path, H5F_ACC_RDONLY_F, f%id, err, access_prp=fapl)
      if (err < 0) call fail(f, 'cannot open it as HDF5 (missing, truncated or not HDF5)')
    end if
    call h5pclose_f(fapl, e2)
    if (.not. f%ok) then
      f%id = -1
      return
    end if
    call h5pcreate_f(H5P_DATASET_XFER_F, f%dxpl, err)
    call h5pset_dxpl_mpio_f(f%dxpl, H5FD_MPIO_COLLECTIVE_F, err)
  end subroutine

  subroutine close_file(f)
    type(ckpt_file_t), intent(inout) :: f
    integer :: err
    if (f%dxpl /= -1) call h5pclose_f(f%dxpl, err)
    if (f%id /= -1) then
      call h5fclose_f(f%id, err)
      if (err < 0) call fail(f, 'closing the file failed')
    end if
    f%id = -1
    f%dxpl = -1
  end subroutine

  !> Runs of consecutive global indices (0-based starts) of ascending gidx.
  pure subroutine runs(gidx, first, count)
    integer, intent(in) :: gidx(:)
    integer(hsize_t), allocatable, intent(out) :: first(:), count(:)
    integer :: k, r, n_runs
    n_runs = 0
    do k = 1, size(gidx)
      if (k == 1) then
        n_runs = 1
      else if (gidx(k) /= gidx(k-1) + 1) then
        n_runs = n_runs + 1
      end if
    end do
    allocate(first(n_runs), count(n_runs))
    r = 0
    do k = 1, size(gidx)
      if (k > 1) then
        if (gidx(k) == gidx(k-1) + 1) then
          count(r) = count(r) + 1
          cycle
        end if
      end if
      r = r + 1
      first(r) = int(gidx(k) - 1, hsize_t)
      count(r) = 1
    end do
  end subroutine

  !> A global float64 dataset, (n_global) for width 0 or (n_global, width),
  !> each rank writing its rows a(max(width,1), n_local) (collective).
  subroutine write_rows(f, name, n_global, width, first, count, gidx, a)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: name
    integer, intent(in) :: n_global, width
    integer(hsize_t), intent(in) :: first(:), count(:)
    integer, intent(in) :: gidx(:)            !< global index of each column of a
    real(rk), intent(in), target :: a(:,:)
    integer(hsize_t) :: fdims(2), start(2), cnt(2)
    integer(hid_t) :: fsid, msid, did
    integer :: rank, err, e2, r, w
    real(rk), target :: dummy(1)
    type(c_ptr) :: p
    if (.not. f%ok) return
    w = max(width, 1)
    rank = merge(1, 2, width == 0)
    fdims = [int(w, hsize_t), int(n_global, hsize_t)]
    if (rank == 1) fdims(1) = int(n_global, hsize_t)
    call h5screate_simple_f(rank, fdims(1:rank), fsid, err)
    call h5dcreate_f(f%id, name, H5T_IEEE_F64LE, fsid, did, err)
    if (err < 0) then
      call fail(f, 'cannot create dataset '//name)
      call h5sclose_f(fsid, e2)
      return
    end if
    if (size(first) == 0) then
      call h5sselect_none_f(fsid, err)
      call h5screate_simple_f(1, [1_hsize_t], msid, err)
      call h5sselect_none_f(msid, err)
      p = c_loc(dummy)
    else
      do r = 1, size(first)
        if (rank == 1) then
          start(1) = first(r); cnt(1) = count(r)
        else
          start = [0_hsize_t, first(r)]; cnt = [int(w, hsize_t), count(r)]
        end if
        call h5sselect_hyperslab_f(fsid, merge(H5S_SELECT_SET_F, H5S_SELECT_OR_F, r == 1), start(1:rank), &
                                   cnt(1:rank), err)
      end do
      if (rank == 1) then
        call h5screate_simple_f(1, [int(size(a, 2), hsize_t)], msid, err)
      else
        call h5screate_simple_f(2, [int(w, hsize_t), int(size(a, 2), hsize_t)], msid, err)
      end if
      p = c_loc(a)
    end if
    call h5dwrite_f(did, h5kind_to_type(rk, H5_REAL_KIND), p, err, mem_space_id=msid, file_space_id=fsid, &
                    xfer_prp=f%dxpl)
    ! a rank whose rows failed (full disk) and one whose did not must leave
    ! the collective calls that follow together
    if (comms_max_int(merge(1, 0, err < 0)) /= 0) call fail(f, 'cannot write dataset '//name)
    call h5sclose_f(msid, e2)
    call h5sclose_f(fsid, e2)
    call h5dclose_f(did, e2)
    f%rows_hash = ieor(f%rows_hash, rows_hash(name, gidx, a))
  end subroutine

  !> Exclusive or of one hash per row (dataset name, global index, values):
  !> the same for any split of the rows over ranks.
  pure integer(i8) function rows_hash(name, gidx, a) result(h)
    character(len=*), intent(in) :: name
    integer, intent(in) :: gidx(:)
    real(rk), intent(in) :: a(:,:)
    integer(i8) :: h_name
    integer :: k
    h_name = hash_text(fnv_offset, name)
    h = 0
    do k = 1, size(gidx)
      h = ieor(h, hash_reals(hash_ints(h_name, gidx(k:k)), a(:,k)))
    end do
  end function

  !> Hash of what every rank holds alike: the scalars and small datasets
  !> (not the provenance: checkpoints_written differs between a chain of
  !> runs and the straight run, and only names the next slot).
  pure integer(i8) function scalars_hash(reals, ints_in, hashes, wall_work, contact_work) result(h)
    real(rk), intent(in) :: reals(:)
    integer, intent(in) :: ints_in(:)
    integer(i8), intent(in) :: hashes(:), wall_work(:), contact_work(:)
    integer :: ints(size(ints_in))
    ints = ints_in
    ints(3) = 0
    h = hash_i8s(hash_i8s(hash_i8s(hash_reals(hash_ints(fnv_offset, ints), reals), hashes), wall_work), &
                 contact_work)
  end function

  !> A small int64 dataset with the same value on every rank (rank 0 writes).
  subroutine write_small_i8(f, name, a)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: name
    integer(i8), intent(in), target :: a(:)
    integer(hid_t) :: sid, did, msid
    integer :: err, e2
    if (.not. f%ok) return
    call h5screate_simple_f(1, [int(size(a), hsize_t)], sid, err)
    call h5dcreate_f(f%id, name, H5T_STD_I64LE, sid, did, err)
    if (err < 0) then
      call fail(f, 'cannot create dataset '//name)
    else
      ! collective transfer: the other ranks take part and select nothing
      call h5screate_simple_f(1, [int(size(a), hsize_t)], msid, err)
      if (.not. comms_is_root()) then
        call h5sselect_none_f(sid, err)
        call h5sselect_none_f(msid, err)
      end if
      call h5dwrite_f(did, h5kind_to_type(i8, H5_INTEGER_KIND), c_loc(a), err, mem_space_id=msid, &
                      file_space_id=sid, xfer_prp=f%dxpl)
      if (err < 0) call fail(f, 'cannot write dataset '//name)
      call h5sclose_f(msid, e2)
      call h5dclose_f(did, e2)
    end if
    call h5sclose_f(sid, e2)
  end subroutine

  subroutine read_small_i8(f, name, a)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: name
    integer(i8), intent(out), target :: a(:)
    integer(hid_t) :: did
    integer :: err, e2
    type(c_ptr) :: p
    call open_dataset(f, name, [size(a)], did)
    if (.not. f%ok) return
    p = c_loc(a)
    call h5dread_f(did, h5kind_to_type(i8, H5_INTEGER_KIND), p, err)
    if (err < 0) call fail(f, 'cannot read dataset '//name//' (file damaged?)')
    call h5dclose_f(did, e2)
  end subroutine

  !> Opens dataset name and checks its Fortran dimensions (C order reversed).
  subroutine open_dataset(f, name, expect, did)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: name
    integer, intent(in) :: expect(:)
    integer(hid_t), intent(out) :: did
    integer(hid_t) :: sid
    integer(hsize_t) :: dims(2), maxdims(2)
    integer :: err, e2, nd
    if (.not. f%ok) return
    call h5dopen_f(f%id, name, did, err)
    if (err < 0) then
      call fail(f, 'dataset '//name//' is missing')
      return
    end if
    call h5dget_space_f(did, sid, err)
    call h5sget_simple_extent_ndims_f(sid, nd, err)
    dims = 0
    if (nd >= 1 .and. nd <= 2) call h5sget_simple_extent_dims_f(sid, dims(1:nd), maxdims(1:nd), err)
    call h5sclose_f(sid, e2)
    if (nd /= size(expect)) then
      call fail(f, 'dataset '//name//' has the wrong shape')
    else if (any(dims(1:nd) /= expect)) then
      call fail(f, 'dataset '//name//' has the wrong shape')
    end if
    if (.not. f%ok) call h5dclose_f(did, e2)
  end subroutine

  !> The whole global dataset into a(width, n) (width 1: a 1-D dataset).
  subroutine read_all(f, name, a)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: name
    real(rk), intent(out), target :: a(:,:)
    integer(hid_t) :: did
    integer :: err, e2, k
    type(c_ptr) :: p
    if (size(a, 1) == 1) then
      call open_dataset(f, name, [size(a, 2)], did)
    else
      call open_dataset(f, name, [size(a, 1), size(a, 2)], did)
    end if
    if (.not. f%ok) return
    p = c_loc(a)
    call h5dread_f(did, h5kind_to_type(rk, H5_REAL_KIND), p, err)
    if (err < 0) call fail(f, 'cannot read dataset '//name//' (file damaged?)')
    call h5dclose_f(did, e2)
    if (f%ok) f%rows_hash = ieor(f%rows_hash, rows_hash(name, [(k, k = 1, size(a, 2))], a))
  end subroutine

  subroutine attr_real(f, loc, name, v)
    type(ckpt_file_t), intent(inout) :: f
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(rk), intent(in), target :: v
    call attr_write(f, loc, name, H5T_IEEE_F64LE, h5kind_to_type(rk, H5_REAL_KIND), c_loc(v))
  end subroutine

  subroutine attr_int(f, loc, name, v)
    type(ckpt_file_t), intent(inout) :: f
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, intent(in), target :: v
    call attr_write(f, loc, name, H5T_STD_I32LE, h5kind_to_type(kind(v), H5_INTEGER_KIND), c_loc(v))
  end subroutine

  !> A fixed-length string attribute on the root group.
  subroutine attr_text(f, name, v)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: name
    character(len=*), intent(in), target :: v
    integer(hid_t) :: t
    integer :: err, e2
    call h5tcopy_f(H5T_C_S1, t, err)
    call h5tset_size_f(t, int(max(len(v), 1), size_t), err)
    call attr_write(f, f%id, name, t, t, c_loc(v))
    call h5tclose_f(t, e2)
  end subroutine

  !> Scalar attribute; every rank calls with the same value (collective).
  subroutine attr_write(f, loc, name, ftype, mtype, p)
    type(ckpt_file_t), intent(inout) :: f
    integer(hid_t), intent(in) :: loc, ftype, mtype
    character(len=*), intent(in) :: name
    type(c_ptr), intent(in) :: p
    integer(hid_t) :: sid, aid
    integer :: err, e2
    if (.not. f%ok) return
    call h5screate_f(H5S_SCALAR_F, sid, err)
    call h5acreate_f(loc, name, ftype, sid, aid, err)
    if (err >= 0) then
      call h5awrite_f(aid, mtype, p, err)
      call h5aclose_f(aid, e2)
    end if
    call h5sclose_f(sid, e2)
    if (err < 0) call fail(f, 'cannot write attribute '//name)
  end subroutine

  subroutine read_attr_real(f, name, v)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: name
    real(rk), intent(out), target :: v
    v = 0
    call attr_read(f, name, h5kind_to_type(rk, H5_REAL_KIND), c_loc(v))
  end subroutine

  subroutine read_attr_int(f, name, v)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: name
    integer, intent(out), target :: v
    v = 0
    call attr_read(f, name, h5kind_to_type(kind(v), H5_INTEGER_KIND), c_loc(v))
  end subroutine

  subroutine read_attr_text(f, name, v)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: name
    character(len=:), allocatable, intent(out) :: v
    character(len=64), target :: buf
    integer(hid_t) :: t
    integer :: err, e2
    buf = ''
    call h5tcopy_f(H5T_C_S1, t, err)
    call h5tset_size_f(t, int(len(buf), size_t), err)
    call attr_read(f, name, t, c_loc(buf))
    call h5tclose_f(t, e2)
    v = trim(buf(1:max(index(buf, achar(0)) - 1, 0)))
    if (index(buf, achar(0)) == 0) v = trim(buf)
  end subroutine

  subroutine attr_read(f, name, mtype, p)
    type(ckpt_file_t), intent(inout) :: f
    character(len=*), intent(in) :: name
    integer(hid_t), intent(in) :: mtype
    type(c_ptr), intent(in) :: p
    integer(hid_t) :: aid
    integer :: err, e2, slash
    type(c_ptr) :: q
    if (.not. f%ok) return
    ! name may be 'group/attribute'
    slash = index(name, '/', back=.true.)
    if (slash > 0) then
      call h5aopen_by_name_f(f%id, name(1:slash-1), name(slash+1:), aid, err)
    else
      call h5aopen_f(f%id, name, aid, err)
    end if
    if (err < 0) then
      call fail(f, 'attribute '//name//' is missing (not a udar checkpoint?)')
      return
    end if
    q = p
    call h5aread_f(aid, mtype, q, err)
    call h5aclose_f(aid, e2)
    if (err < 0) call fail(f, 'cannot read attribute '//name)
  end subroutine
end module udar_checkpoint
