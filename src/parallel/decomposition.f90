!> What a domain decomposition gives each rank: owned and ghost elements
!> and nodes. Pure computation (no MPI), for the start-up report and
!> `udar --check --ranks N`; the distributed run builds on the same rules.
!> Rules: an element belongs to the rank METIS gives it; a node belongs to
!> the rank of its lowest-id incident element; a rank's ghost elements are
!> the others that touch one of its nodes (it needs them to assemble its
!> nodes' forces in the fixed order), its ghost nodes the others' nodes of
!> its owned and ghost elements.
module udar_decomposition
  implicit none
  private
  public :: rank_counts_t, decomposition_counts

  type, public :: rank_counts_t
    integer :: owned_elems = 0, owned_nodes = 0, ghost_elems = 0, ghost_nodes = 0
  end type

contains

  !> Counts for every rank 0..n_parts-1 in O(elements + nodes) overall.
  !> nd_el_ptr/nd_el: node -> elements, ascending element id.
  pure subroutine decomposition_counts(conn, nd_el_ptr, nd_el, part, n_parts, counts)
    integer, intent(in) :: conn(:,:), nd_el_ptr(:), nd_el(:), part(:), n_parts
    type(rank_counts_t), intent(out) :: counts(0:n_parts-1)
    integer, allocatable :: node_owner(:), elem_stamp(:), node_stamp(:), first(:), members(:), fill(:)
    integer :: n_nodes, n_elems, n, e, r, k, i
    n_nodes = size(nd_el_ptr) - 1
    n_elems = size(part)
    allocate(node_owner(n_nodes), elem_stamp(n_elems), node_stamp(n_nodes))
    do n = 1, n_nodes
      node_owner(n) = part(nd_el(nd_el_ptr(n)))
    end do
    ! each rank's members: its owned elements (as e) then owned nodes (as -n)
    allocate(first(0:n_parts), source=0)
    do e = 1, n_elems
      first(part(e) + 1) = first(part(e) + 1) + 1
    end do
    do n = 1, n_nodes
      first(node_owner(n) + 1) = first(node_owner(n) + 1) + 1
    end do
    do r = 1, n_parts
      first(r) = first(r) + first(r - 1)
    end do
    allocate(members(first(n_parts)), fill(0:n_parts-1))
    fill = first(0:n_parts-1)
    do e = 1, n_elems
      fill(part(e)) = fill(part(e)) + 1
      members(fill(part(e))) = e
    end do
    do n = 1, n_nodes
      fill(node_owner(n)) = fill(node_owner(n)) + 1
      members(fill(node_owner(n))) = -n
    end do
    elem_stamp = -1
    node_stamp = -1
    do r = 0, n_parts - 1
      do i = first(r) + 1, first(r + 1)
        if (members(i) > 0) then
          e = members(i)
          counts(r)%owned_elems = counts(r)%owned_elems + 1
          call visit(e, r, conn, part, node_owner, elem_stamp, node_stamp, counts(r))
        else
          n = -members(i)
          counts(r)%owned_nodes = counts(r)%owned_nodes + 1
          do k = nd_el_ptr(n), nd_el_ptr(n + 1) - 1
            call visit(nd_el(k), r, conn, part, node_owner, elem_stamp, node_stamp, counts(r))
          end do
        end if
      end do
    end do
  end subroutine

  !> First visit of element el by rank r: count it and its nodes as ghosts
  !> where r does not own them.
  pure subroutine visit(el, r, conn, part, node_owner, elem_stamp, node_stamp, c)
    integer, intent(in) :: el, r, conn(:,:), part(:), node_owner(:)
    integer, intent(inout) :: elem_stamp(:), node_stamp(:)
    type(rank_counts_t), intent(inout) :: c
    integer :: a, m
    if (elem_stamp(el) == r) return
    elem_stamp(el) = r
    if (part(el) /= r) c%ghost_elems = c%ghost_elems + 1
    do a = 1, size(conn, 2)
      m = conn(el, a)
      if (node_stamp(m) == r) cycle
      node_stamp(m) = r
      if (node_owner(m) /= r) c%ghost_nodes = c%ghost_nodes + 1
    end do
  end subroutine
end module udar_decomposition
