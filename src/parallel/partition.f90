!> Element partition for the domain decomposition: which rank owns which
!> tetrahedron. Pure computation (no MPI): the face-adjacency (dual) graph is
!> built here, deterministically, and cut with METIS_PartGraphKway.
!>
!> Determinism: the dual graph depends only on conn (faces are ordered by a
!> stable counting sort of their sorted node triples; adjacency rows are sorted
!> ascending), and METIS is called with a fixed seed and fixed options, so the
!> same mesh gives the same partition on every run and on every rank that
!> calls this. Nothing here depends on the rank count except n_parts.
!>
!> Contiguity: METIS only honours METIS_OPTION_CONTIG on a connected graph (it
!> rejects disconnected input), but meshes with several bodies (projectile +
!> plate) have a disconnected dual graph. The graph given to METIS therefore
!> gets one artificial "bridge" edge between the lowest-numbered elements of
!> consecutive connected components; with CONTIG on, every part is then a
!> single face-connected piece within each body it touches. Bridges are not
!> counted in the reported edge cut.
module udar_partition
  use, intrinsic :: iso_c_binding, only: c_int, c_int32_t, c_float, c_ptr, c_null_ptr, c_loc
  use udar_kinds, only: rk, i8
  use udar_ordering, only: sorted_ints
  implicit none
  private
  public :: partition_elements, partition_stats_t, metis_idx_width_ok

  type, public :: partition_stats_t
    integer :: n_parts = 0, edge_cut = 0
    real(rk) :: imbalance = 0      !< max part size / mean part size
    real(rk) :: weighted_imbalance = 0   !< the same of the parts' summed weights (with weights)
    integer, allocatable :: part_size(:)
  end type

  ! The kinds this METIS build was compiled with (metis.h: IDXTYPEWIDTH 32,
  ! REALTYPEWIDTH 32); metis_idx_width_ok() verifies them at run time.
  integer, parameter :: idx_t = c_int32_t
  integer, parameter :: real_t = c_float

  integer, parameter :: metis_noptions = 40
  integer(c_int), parameter :: metis_ok = 1
  ! options(:) indices: the C enum value (moptions_et) + 1
  integer, parameter :: opt_objtype = 1 + 1, opt_seed = 8 + 1, opt_contig = 11 + 1, &
                        opt_numbering = 17 + 1
  integer(idx_t), parameter :: metis_objtype_cut = 0
  integer(idx_t), parameter :: metis_seed = 1

  interface
    function c_metis_set_default_options(options) bind(c, name='METIS_SetDefaultOptions') result(rc)
      import :: c_int, idx_t
      integer(idx_t), intent(inout) :: options(*)
      integer(c_int) :: rc
    end function

    ! Optional arrays (vwgt, vsize, adjwgt, tpwgts, ubvec) are pointers so
    ! that NULL can be passed; idx_t scalars are passed by reference as in C.
    function c_metis_part_graph_kway(nvtxs, ncon, xadj, adjncy, vwgt, vsize, adjwgt, nparts, &
                                     tpwgts, ubvec, options, edgecut, part) &
        bind(c, name='METIS_PartGraphKway') result(rc)
      import :: c_int, c_ptr, idx_t
      integer(idx_t), intent(inout) :: nvtxs, ncon, nparts
      integer(idx_t), intent(inout) :: xadj(*), adjncy(*)
      type(c_ptr), value :: vwgt, vsize, adjwgt, tpwgts, ubvec
      integer(idx_t), intent(inout) :: options(*)
      integer(idx_t), intent(out) :: edgecut
      integer(idx_t), intent(inout) :: part(*)
      integer(c_int) :: rc
    end function
  end interface

contains

  !> Partitions the elements of conn(n_elems,4) (tetrahedra; 2D: (n_elems,3)
  !> triangles, connected through edges) into n_parts face-connected,
  !> balanced parts (part(e) in 0..n_parts-1): balanced in element count,
  !> or with weights (>= 1 each) in their sums (METIS vertex weights: the
  !> elements' costs). n_parts >= n_elems puts one element in each of the
  !> first n_elems parts and leaves the rest empty (METIS is not called:
  !> that is the optimum and METIS misbehaves there).
  subroutine partition_elements(n_nodes, conn, n_parts, part, stats, ok, errmsg, weights)
    integer, intent(in) :: n_nodes, conn(:,:)
    integer, intent(in) :: n_parts
    integer, intent(out) :: part(:)
    type(partition_stats_t), intent(out) :: stats
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: errmsg
    integer, intent(in), optional :: weights(:)
    integer, allocatable :: xadj(:), adjncy(:), comp_first(:)
    integer :: n_elems, e, k, n_comp
    character(len=160) :: buf

    ok = .false.
    errmsg = ''
    n_elems = size(conn, 1)
    if (n_parts < 1) then
      write (buf, '(a,i0)') 'partition: number of parts must be >= 1, got ', n_parts
      errmsg = trim(buf); return
    end if
    if (size(conn, 2) /= 4 .and. size(conn, 2) /= 3) then
      write (buf, '(a,i0)') 'partition: conn must have 4 (tet4) or 3 (tri3) columns, got ', size(conn, 2)
      errmsg = trim(buf); return
    end if
    if (size(part) /= n_elems) then
      write (buf, '(a,i0,a,i0)') 'partition: part has size ', size(part), ', expected ', n_elems
      errmsg = trim(buf); return
    end if
    if (present(weights)) then
      if (size(weights) /= n_elems) then
        write (buf, '(a,i0,a,i0)') 'partition: weights has size ', size(weights), ', expected ', n_elems
        errmsg = trim(buf); return
      end if
      if (n_elems > 0) then
        if (minval(weights) < 1) then
          errmsg = 'partition: element weights must be >= 1'; return
        end if
      end if
    end if
    ! 4 faces per element and 2 directed entries per edge must fit in int32
    if (4_i8*n_elems > huge(n_elems)) then
      errmsg = 'partition: too many elements for 32-bit graph indices'; return
    end if
    if (n_elems > 0) then
      if (minval(conn) < 1 .or. maxval(conn) > n_nodes) then
        write (buf, '(a,i0,a)') 'partition: node index outside 1..', n_nodes, ' in conn'
        errmsg = trim(buf); return
      end if
    end if

    part = 0
    if (n_parts >= n_elems) then
      part = [(e - 1, e = 1, n_elems)]
    end if

    if (n_elems > 0) call dual_graph(n_nodes, conn, xadj, adjncy)

    if (n_parts > 1 .and. n_parts < n_elems) then
      if (.not. metis_idx_width_ok()) then
        errmsg = 'partition: the METIS library does not use 32-bit idx_t and real_t '// &
                 '(IDXTYPEWIDTH/REALTYPEWIDTH); udar is built for the 32-bit METIS'
        return
      end if
      call components(xadj, adjncy, n_comp, comp_first)
      call metis_kway(xadj, adjncy, comp_first(1:n_comp), n_parts, part, errmsg, weights)
      if (len(errmsg) > 0) return
    end if

    ! stats from the real dual graph (bridges excluded)
    stats%n_parts = n_parts
    allocate(stats%part_size(0:n_parts - 1), source=0)
    do e = 1, n_elems
      stats%part_size(part(e)) = stats%part_size(part(e)) + 1
    end do
    stats%edge_cut = 0
    do e = 1, n_elems
      do k = xadj(e) + 1, xadj(e + 1)
        if (adjncy(k) + 1 > e .and. part(adjncy(k) + 1) /= part(e)) stats%edge_cut = stats%edge_cut + 1
      end do
    end do
    if (n_elems > 0) then
      stats%imbalance = real(maxval(stats%part_size), rk)*real(n_parts, rk)/real(n_elems, rk)
    else
      stats%imbalance = 0   ! nothing to balance
    end if
    stats%weighted_imbalance = stats%imbalance
    if (present(weights) .and. n_elems > 0) then
      block
        integer(i8) :: sums(0:n_parts-1)
        sums = 0
        do e = 1, n_elems
          sums(part(e)) = sums(part(e)) + weights(e)
        end do
        stats%weighted_imbalance = real(maxval(sums), rk)*real(n_parts, rk)/real(sum(sums), rk)
      end block
    end if
    ok = .true.
  end subroutine

  !> Face-adjacency graph in 0-based CSR (METIS layout): rows sorted ascending,
  !> no self loops, no duplicates. Faces shared by more than two elements (a
  !> non-conforming mesh) connect every pair rather than failing. An
  !> element's face j is its corners but the j-th (a triangle's: an edge).
  subroutine dual_graph(n_nodes, conn, xadj, adjncy)
    integer, intent(in) :: n_nodes, conn(:,:)
    integer, allocatable, intent(out) :: xadj(:), adjncy(:)
    integer, allocatable :: key(:,:), order(:), tmp(:), cnt(:), ea(:), eb(:)
    integer :: n_elems, n_faces, f, e, j, pass, i0, i1, i, k, n_edges, a, b, nc, m

    n_elems = size(conn, 1)
    nc = size(conn, 2)
    m = nc - 1
    n_faces = nc*n_elems
    allocate(key(m, n_faces), order(n_faces), tmp(n_faces), cnt(0:n_nodes))
    ! face f = nc*(e-1)+j: its sorted nodes
    do e = 1, n_elems
      do j = 1, nc
        f = nc*(e - 1) + j
        key(:, f) = sorted_ints(pack(conn(e, :), [(i /= j, i = 1, nc)]))
      end do
    end do
    ! stable LSD counting sort on the nodes, last first: O(faces + nodes), fully deterministic
    order = [(f, f = 1, n_faces)]
    do pass = m, 1, -1
      cnt = 0
      do f = 1, n_faces
        cnt(key(pass, f)) = cnt(key(pass, f)) + 1
      end do
      do i = 1, n_nodes
        cnt(i) = cnt(i) + cnt(i - 1)
      end do
      do i = n_faces, 1, -1
        f = order(i)
        tmp(cnt(key(pass, f))) = f
        cnt(key(pass, f)) = cnt(key(pass, f)) - 1
      end do
      order = tmp
    end do
    deallocate(tmp, cnt)

    ! equal keys are adjacent: each run of equal faces gives edges
    allocate(ea(2*n_elems + 8), eb(2*n_elems + 8))
    n_edges = 0
    i0 = 1
    do while (i0 <= n_faces)
      i1 = i0
      do while (i1 < n_faces)
        f = order(i1 + 1); j = order(i0)
        if (any(key(:, f) /= key(:, j))) exit
        i1 = i1 + 1
      end do
      do i = i0, i1 - 1
        do k = i + 1, i1
          a = (order(i) - 1)/nc + 1
          b = (order(k) - 1)/nc + 1
          if (a == b) cycle        ! degenerate element with a repeated face
          if (n_edges == size(ea)) call grow2(ea, eb)
          n_edges = n_edges + 1
          ea(n_edges) = a; eb(n_edges) = b
        end do
      end do
      i0 = i1 + 1
    end do
    deallocate(key, order)
    call edges_to_csr(n_elems, ea(1:n_edges), eb(1:n_edges), xadj, adjncy)
  end subroutine

  !> Symmetric 0-based CSR from an undirected edge list; rows sorted, duplicates dropped.
  subroutine edges_to_csr(n, ea, eb, xadj, adjncy)
    integer, intent(in) :: n, ea(:), eb(:)
    integer, allocatable, intent(out) :: xadj(:), adjncy(:)
    integer, allocatable :: deg(:), fill(:), tmp(:)
    integer :: i, v, lo, hi, m

    allocate(deg(n), source=0)
    do i = 1, size(ea)
      deg(ea(i)) = deg(ea(i)) + 1
      deg(eb(i)) = deg(eb(i)) + 1
    end do
    allocate(xadj(n + 1), fill(n))
    xadj(1) = 0
    do v = 1, n
      xadj(v + 1) = xadj(v) + deg(v)
    end do
    fill = xadj(1:n)
    allocate(tmp(xadj(n + 1)))
    do i = 1, size(ea)
      fill(ea(i)) = fill(ea(i)) + 1; tmp(fill(ea(i))) = eb(i) - 1
      fill(eb(i)) = fill(eb(i)) + 1; tmp(fill(eb(i))) = ea(i) - 1
    end do
    ! rows are short (4 for a conforming tet mesh): insertion sort, then compact
    m = 0
    do v = 1, n
      lo = xadj(v) + 1; hi = xadj(v + 1)
      tmp(lo:hi) = sorted_ints(tmp(lo:hi))
      xadj(v) = m
      do i = lo, hi
        if (i > lo) then
          if (tmp(i) == tmp(i - 1)) cycle
        end if
        m = m + 1
        tmp(m) = tmp(i)
      end do
    end do
    xadj(n + 1) = m
    adjncy = tmp(1:m)
  end subroutine

  !> Connected components by BFS from the lowest unvisited element:
  !> comp_first(c) is the lowest element (1-based) of component c.
  subroutine components(xadj, adjncy, n_comp, comp_first)
    integer, intent(in) :: xadj(:), adjncy(:)
    integer, intent(out) :: n_comp
    integer, allocatable, intent(out) :: comp_first(:)
    logical, allocatable :: seen(:)
    integer, allocatable :: queue(:)
    integer :: n, s, head, tail, v, k, w

    n = size(xadj) - 1
    allocate(seen(n), source=.false.)
    allocate(queue(n), comp_first(n))
    n_comp = 0
    do s = 1, n
      if (seen(s)) cycle
      n_comp = n_comp + 1
      comp_first(n_comp) = s
      seen(s) = .true.
      head = 1; tail = 1; queue(1) = s
      do while (head <= tail)
        v = queue(head); head = head + 1
        do k = xadj(v) + 1, xadj(v + 1)
          w = adjncy(k) + 1
          if (.not. seen(w)) then
            seen(w) = .true.
            tail = tail + 1; queue(tail) = w
          end if
        end do
      end do
    end do
  end subroutine

  !> METIS_PartGraphKway on the dual graph plus bridges between consecutive
  !> components, edge-cut objective, fixed seed, CONTIG, default ufactor (1.03).
  subroutine metis_kway(xadj, adjncy, comp_first, n_parts, part, errmsg, weights)
    integer, intent(in) :: xadj(:), adjncy(:), comp_first(:)
    integer, intent(in) :: n_parts
    integer, intent(inout) :: part(:)
    character(len=:), allocatable, intent(inout) :: errmsg
    integer, intent(in), optional :: weights(:)
    integer, allocatable :: ea(:), eb(:), bx(:), badj(:)
    integer(idx_t), allocatable :: m_xadj(:), m_adjncy(:), m_part(:)
    integer(idx_t), allocatable, target :: m_vwgt(:)
    type(c_ptr) :: vwgt
    integer(idx_t) :: options(metis_noptions), nvtxs, ncon, nparts, objval
    integer(c_int) :: rc
    integer :: n, v, k, m, nb
    character(len=160) :: buf

    n = size(xadj) - 1
    nb = size(comp_first) - 1
    if (nb > 0) then
      ! real edges once each (v < w) plus the bridges, rebuilt as one CSR
      allocate(ea(xadj(n + 1)/2 + nb), eb(xadj(n + 1)/2 + nb))
      m = 0
      do v = 1, n
        do k = xadj(v) + 1, xadj(v + 1)
          if (adjncy(k) + 1 > v) then
            m = m + 1; ea(m) = v; eb(m) = adjncy(k) + 1
          end if
        end do
      end do
      do k = 1, nb
        m = m + 1; ea(m) = comp_first(k); eb(m) = comp_first(k + 1)
      end do
      call edges_to_csr(n, ea(1:m), eb(1:m), bx, badj)
      allocate(m_xadj, source=int(bx, idx_t))
      allocate(m_adjncy(max(size(badj), 1)), source=0_idx_t)   ! never empty: passed by address
      m_adjncy(1:size(badj)) = int(badj, idx_t)
    else
      allocate(m_xadj, source=int(xadj, idx_t))
      allocate(m_adjncy(max(size(adjncy), 1)), source=0_idx_t)
      m_adjncy(1:size(adjncy)) = int(adjncy, idx_t)
    end if

    rc = c_metis_set_default_options(options)
    if (rc /= metis_ok) then
      errmsg = 'partition: METIS_SetDefaultOptions failed'; return
    end if
    options(opt_objtype) = metis_objtype_cut
    options(opt_seed) = metis_seed
    options(opt_contig) = 1
    options(opt_numbering) = 0

    nvtxs = int(n, idx_t)
    ncon = 1
    nparts = int(n_parts, idx_t)
    allocate(m_part(n), source=0_idx_t)
    vwgt = c_null_ptr
    if (present(weights)) then
      allocate(m_vwgt, source=int(weights, idx_t))
      vwgt = c_loc(m_vwgt)
    end if
    rc = c_metis_part_graph_kway(nvtxs, ncon, m_xadj, m_adjncy, vwgt, c_null_ptr, c_null_ptr, &
                                 nparts, c_null_ptr, c_null_ptr, options, objval, m_part)
    if (rc /= metis_ok) then
      write (buf, '(a,i0)') 'partition: METIS_PartGraphKway failed with status ', rc
      errmsg = trim(buf); return
    end if
    if (any(m_part < 0 .or. m_part >= nparts)) then
      errmsg = 'partition: METIS returned a part number out of range'; return
    end if
    part = int(m_part)
  end subroutine

  !> True when the linked METIS uses 32-bit idx_t and 32-bit real_t.
  !> idx_t: METIS_SetDefaultOptions sets all METIS_NOPTIONS (40) entries to
  !> -1; it is given an 80-entry int32 buffer pre-filled with a sentinel, so a
  !> 32-bit build writes exactly entries 1..40 and a 64-bit build all 80 (no
  !> overflow either way). real_t: only then (so idx_t arrays are read
  !> correctly) a 2-way METIS_PartGraphKway of a 4-vertex path is run with
  !> float tpwgts = (0.5, 0.5) in a 4-float buffer padded with zeros; read as
  !> doubles they would be (garbage, 0.0), which METIS rejects (target weights
  !> must be positive and sum to 1), so success means real_t is float.
  function metis_idx_width_ok() result(ok)
    logical :: ok
    integer(c_int32_t), parameter :: sentinel = 123456789
    integer(c_int32_t) :: buf(2*metis_noptions), options(metis_noptions)
    integer(idx_t) :: xadj(5), adjncy(6), part(4), nvtxs, ncon, nparts, objval
    real(real_t), target :: tpwgts(4)
    integer(c_int) :: rc

    ok = .false.
    buf = sentinel
    rc = c_metis_set_default_options(buf)
    if (rc /= metis_ok) return
    if (any(buf(1:metis_noptions) /= -1)) return
    if (any(buf(metis_noptions + 1:) /= sentinel)) return

    options = buf(1:metis_noptions)
    options(opt_seed) = metis_seed
    options(opt_numbering) = 0
    xadj = [0, 1, 3, 5, 6]
    adjncy = [1, 0, 2, 1, 3, 2]
    tpwgts = [0.5_real_t, 0.5_real_t, 0.0_real_t, 0.0_real_t]
    nvtxs = 4; ncon = 1; nparts = 2
    part = -1
    rc = c_metis_part_graph_kway(nvtxs, ncon, xadj, adjncy, c_null_ptr, c_null_ptr, c_null_ptr, &
                                 nparts, c_loc(tpwgts), c_null_ptr, options, objval, part)
    if (rc /= metis_ok) return
    ok = all(part >= 0 .and. part <= 1)
  end function

  pure subroutine grow2(a, b)
    integer, allocatable, intent(inout) :: a(:), b(:)
    integer, allocatable :: t(:)
    allocate(t(2*size(a)))
    t(1:size(a)) = a
    call move_alloc(t, a)
    allocate(t(2*size(b)))
    t(1:size(b)) = b
    call move_alloc(t, b)
  end subroutine

end module udar_partition
