!> Unit test of the decomposition counts on hand-checked meshes.
program test_decomposition
  use udar_decomposition, only: rank_counts_t, decomposition_counts
  implicit none
  integer :: n_fail = 0
  type(rank_counts_t) :: c2(0:1), c3(0:2)
  integer, allocatable :: conn(:,:), ptr(:), lst(:)

  ! two tets sharing the face 2-3-4; ranks 0 and 1
  conn = reshape([1, 2, 2, 3, 3, 4, 4, 5], [2, 4])
  call incidence(conn, 5, ptr, lst)
  call decomposition_counts(conn, ptr, lst, [0, 1], 2, c2)
  ! nodes 1-4 belong to rank 0 (element 1 is their lowest), node 5 to rank 1
  call check('rank0', same(c2(0), rank_counts_t(1, 4, 1, 1)), c2(0))
  call check('rank1', same(c2(1), rank_counts_t(1, 1, 0, 3)), c2(1))
  ! a strip of three tets 1-2-3-4, 2-3-4-5, 3-4-5-6 on three ranks
  conn = reshape([1, 2, 3, 2, 3, 4, 3, 4, 5, 4, 5, 6], [3, 4])
  call incidence(conn, 6, ptr, lst)
  call decomposition_counts(conn, ptr, lst, [0, 1, 2], 3, c3)
  call check('strip_rank0', same(c3(0), rank_counts_t(1, 4, 2, 2)), c3(0))
  call check('strip_rank1', same(c3(1), rank_counts_t(1, 1, 1, 4)), c3(1))   ! ghosts: element 3, nodes 2, 3, 4, 6
  call check('strip_rank2', same(c3(2), rank_counts_t(1, 1, 0, 3)), c3(2))
  ! one rank: nothing is a ghost
  call decomposition_counts(conn, ptr, lst, [0, 0, 0], 1, c3(0:0))
  call check('one_rank', same(c3(0), rank_counts_t(3, 6, 0, 0)), c3(0))
  if (n_fail > 0) error stop 1

contains

  logical function same(a, b)
    type(rank_counts_t), intent(in) :: a, b
    same = a%owned_elems == b%owned_elems .and. a%owned_nodes == b%owned_nodes .and. &
           a%ghost_elems == b%ghost_elems .and. a%ghost_nodes == b%ghost_nodes
  end function

  subroutine check(name, cond, c)
    character(len=*), intent(in) :: name
    logical, intent(in) :: cond
    type(rank_counts_t), intent(in) :: c
    character(len=120) :: buf
    write(buf, '(a,4(1x,i0))') 'owned elems/nodes, ghost elems/nodes:', c%owned_elems, c%owned_nodes, &
      c%ghost_elems, c%ghost_nodes
    if (cond) then
      print '(a)', 'PASS '//name//': '//trim(buf)
    else
      print '(a)', 'FAIL '//name//': '//trim(buf)
      n_fail = n_fail + 1
    end if
  end subroutine

  subroutine incidence(conn, n_nodes, ptr, lst)
    integer, intent(in) :: conn(:,:), n_nodes
    integer, allocatable, intent(out) :: ptr(:), lst(:)
    integer :: e, a, n, k
    allocate(ptr(n_nodes + 1), source=0)
    do e = 1, size(conn, 1)
      do a = 1, 4
        ptr(conn(e,a) + 1) = ptr(conn(e,a) + 1) + 1
      end do
    end do
    ptr(1) = 1
    do n = 1, n_nodes
      ptr(n + 1) = ptr(n + 1) + ptr(n)
    end do
    allocate(lst(ptr(n_nodes + 1) - 1))
    k = 0
    do n = 1, n_nodes
      do e = 1, size(conn, 1)
        if (any(conn(e,:) == n)) then
          k = k + 1
          lst(k) = e
        end if
      end do
    end do
  end subroutine
end program test_decomposition
