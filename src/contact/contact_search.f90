!> Bucket search for contact: a uniform grid of cubic cells over the master
!> triangles' bounding boxes (widened by the search margin); a slave node
!> looks only at the triangles listed in its own cell. Built by counting
!> sort in O(triangles + cells); a query is O(1) for a reasonable mesh.
!> Pure kernels on an explicit grid type: no module state.
module udar_contact_search
  use udar_kinds, only: rk
  implicit none
  private
  public :: bucket_grid_t, grid_build, grid_cell, ensure

  !> Grows an allocatable array to hold at least n (by half again: few
  !> reallocations), keeping its contents if asked.
  interface ensure
    module procedure ensure_int, ensure_real
  end interface

  type, public :: bucket_grid_t
    real(rk) :: lo(3) = 0, cell = 1       !< m: grid origin, cell edge
    integer :: n(3) = 1                    !< cells per direction
    integer, allocatable :: start(:)       !< CSR over cells (size n1*n2*n3 + 1)
    integer, allocatable :: items(:)       !< triangle indices, ascending in each cell
    integer, allocatable :: fill(:)        !< work: next free slot of each cell
  end type

  !> At most this many cells, and this many cell entries, per triangle on
  !> average: bounds the memory when a few triangles are much larger than
  !> the rest.
  integer, parameter :: max_cells_per_triangle = 8, max_entries_per_triangle = 16

contains

  !> Grid over boxes [lo(:,t), hi(:,t)] (already widened by the margin).
  pure subroutine grid_build(grid, box_lo, box_hi)
    type(bucket_grid_t), intent(inout) :: grid
    real(rk), intent(in) :: box_lo(:,:), box_hi(:,:)
    integer :: nt, t, i, j, k, c, n_cells, pass
    integer :: c_lo(3), c_hi(3)
    real(rk) :: extent(3), size_mean, entries
    nt = size(box_lo, 2)
    if (nt == 0) then
      grid%n = 1
      call ensure(grid%start, 2)
      grid%start(1:2) = 1
      return
    end if
    grid%lo = minval(box_lo, dim=2)
    extent = maxval(box_hi, dim=2) - grid%lo
    ! cells as large as the boxes on average, not as the largest: on a
    ! graded mesh, or with a few stretched faces, cells that large hold
    ! hundreds of the fine region's boxes, which every node there tests;
    ! a large box covers many cells instead (the candidates a point finds,
    ! the boxes that hold it, in ascending order, do not depend on the cell)
    size_mean = 0
    do t = 1, nt
      size_mean = size_mean + maxval(box_hi(:,t) - box_lo(:,t))
    end do
    size_mean = size_mean/nt
    grid%cell = max(size_mean, maxval(extent)*1.0e-6_rk, tiny(1.0_rk))
    do
      grid%n = max(1, ceiling(extent/grid%cell))
      if (real(grid%n(1), rk)*grid%n(2)*grid%n(3) <= real(max_cells_per_triangle, rk)*nt + 8) then
        entries = 0
        do t = 1, nt
          call cell_range(grid, box_lo(:,t), box_hi(:,t), c_lo, c_hi)
          entries = entries + product(real(c_hi - c_lo + 1, rk))
        end do
        if (entries <= real(max_entries_per_triangle, rk)*nt + 8) exit
      end if
      grid%cell = grid%cell*1.25_rk
    end do
    n_cells = grid%n(1)*grid%n(2)*grid%n(3)
    ! the arrays grow when needed and are kept: no allocation in a steady run
    call ensure(grid%start, n_cells + 1)
    call ensure(grid%fill, n_cells)
    grid%start(1:n_cells+1) = 0
    ! two sweeps over the boxes' cells: count, then (after the prefix sum)
    ! fill; triangles end up in ascending order in every cell
    do pass = 1, 2
      if (pass == 2) then
        grid%start(1) = 1
        do c = 1, n_cells
          grid%start(c + 1) = grid%start(c + 1) + grid%start(c)
        end do
        call ensure(grid%items, grid%start(n_cells + 1) - 1)
        grid%fill(1:n_cells) = grid%start(1:n_cells)
      end if
      do t = 1, nt
        call cell_range(grid, box_lo(:,t), box_hi(:,t), c_lo, c_hi)
        do k = c_lo(3), c_hi(3)
          do j = c_lo(2), c_hi(2)
            do i = c_lo(1), c_hi(1)
              c = cell_index(grid, i, j, k)
              if (pass == 1) then
                grid%start(c + 1) = grid%start(c + 1) + 1
              else
                grid%items(grid%fill(c)) = t
                grid%fill(c) = grid%fill(c) + 1
              end if
            end do
          end do
        end do
      end do
    end do
  end subroutine

  !> a has at least n entries (grown by half again when too small); with
  !> keep, its entries so far are kept.
  pure subroutine ensure_int(a, n, keep)
    integer, allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    logical, intent(in), optional :: keep
    integer, allocatable :: b(:)
    if (.not. allocated(a)) then
      allocate(a(max(n, 3*n/2, 1)))
      return
    end if
    if (size(a) >= n) return
    allocate(b(max(n, 3*n/2, 1)))
    if (present(keep)) then
      if (keep) b(1:size(a)) = a
    end if
    call move_alloc(b, a)
  end subroutine

  !> As ensure_int, for reals.
  pure subroutine ensure_real(a, n, keep)
    real(rk), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    logical, intent(in), optional :: keep
    real(rk), allocatable :: b(:)
    if (.not. allocated(a)) then
      allocate(a(max(n, 3*n/2, 1)))
      return
    end if
    if (size(a) >= n) return
    allocate(b(max(n, 3*n/2, 1)))
    if (present(keep)) then
      if (keep) b(1:size(a)) = a
    end if
    call move_alloc(b, a)
  end subroutine

  !> The cell holding point p, or 0 when p is outside the grid.
  pure integer function grid_cell(grid, p) result(c)
    type(bucket_grid_t), intent(in) :: grid
    real(rk), intent(in) :: p(3)
    integer :: ijk(3)
    c = 0
    if (any(p < grid%lo)) return
    ijk = int((p - grid%lo)/grid%cell) + 1
    if (any(ijk > grid%n)) then
      ! the upper faces of the grid belong to the last cells
      if (any(p > grid%lo + grid%n*grid%cell)) return
      ijk = min(ijk, grid%n)
    end if
    c = cell_index(grid, ijk(1), ijk(2), ijk(3))
  end function

  pure subroutine cell_range(grid, lo, hi, c_lo, c_hi)
    type(bucket_grid_t), intent(in) :: grid
    real(rk), intent(in) :: lo(3), hi(3)
    integer, intent(out) :: c_lo(3), c_hi(3)
    c_lo = min(max(int((lo - grid%lo)/grid%cell) + 1, 1), grid%n)
    c_hi = min(max(int((hi - grid%lo)/grid%cell) + 1, 1), grid%n)
  end subroutine

  pure integer function cell_index(grid, i, j, k)
    type(bucket_grid_t), intent(in) :: grid
    integer, intent(in) :: i, j, k
    cell_index = i + grid%n(1)*((j - 1) + grid%n(2)*(k - 1))
  end function
end module udar_contact_search
