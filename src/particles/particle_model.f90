!> The particles that eroded elements of `eroded = 'particles'` materials
!> become (issue 15, theory.md section 15): structure of arrays, the same
!> on every rank (every rank holds and advances all of them, in the order
!> they were made: by cycle, then ascending element id), and the work
!> arrays of their step. Grown by doubling when a conversion needs room,
!> never in a cycle without one.
module udar_particle_model
  use udar_kinds, only: rk
  implicit none
  private
  public :: particles_t, particles_reserve, particles_pair_room

  type :: particles_t
    logical :: enabled = .false.          !< some material's eroded elements become particles
    integer :: dim = 3                    !< the kernel's dimension: 3, or 2 in plane strain (masses per metre) and axisymmetric
    logical :: axisymmetric = .false.     !< x(1) = r, x(2) the axis, masses per revolution (the area density's sums)
    integer :: n = 0                      !< particles made so far
    real(rk), allocatable :: x(:,:), v(:,:)   !< (3,n) m, m/s: position x(n), velocity v(n-1/2) as the nodes'
    real(rk), allocatable :: m(:)         !< kg
    real(rk), allocatable :: rho(:)       !< kg/m3, density (continuity equation)
    real(rk), allocatable :: e(:)         !< J/kg, specific internal energy
    real(rk), allocatable :: p(:), c(:)   !< Pa, m/s: pressure (no tension) and sound speed at rho, e
    real(rk), allocatable :: h(:)         !< m, smoothing length (fixed at conversion)
    real(rk), allocatable :: temp(:), eps_p(:)   !< K, -: temperature and equivalent plastic strain (the element's at conversion)
    !> strength kept (made from an element that had not fractured, and not
    !> fractured since): deviatoric stress s (6,n) Pa (xx,yy,zz,xy,yz,zx),
    !> the flow stress's hardening part (Pa) and thermal factor, the damage
    logical, allocatable :: strong(:)
    real(rk), allocatable :: s(:,:), hard(:), soft(:), damage(:)
    integer, allocatable :: mat(:), part(:)      !< material and part of the element it was
    integer, allocatable :: elem(:)       !< global element index (1-based) it was
    logical, allocatable :: converted(:)  !< (local elements) already made a particle
    integer, allocatable :: counts(:)     !< (0:ranks-1) work: reals of conversion records from each rank
    real(rk), allocatable :: send(:)      !< work: this rank's conversion records (grown when needed)
    real(rk) :: heat = 0                  !< J, kinetic energy of the corners' relative motion made heat at conversion
    real(rk) :: dt_stable = huge(1.0_rk)  !< s, the particles' stable step after their last step
    ! work arrays of a step
    real(rk), allocatable :: acc(:,:), drho(:), dheat(:), vsig(:), visc(:)
    real(rk), allocatable :: grad(:,:)    !< (9,n) sum_j m_j v_ij (x) grad_i W_ij (sph_rates)
    real(rk), allocatable :: r_art(:,:), art_eps(:)   !< (6,n+images) m2/s2 artificial stress of the step, and its eps
    logical :: artificial = .false.       !< some particle's material has an artificial stress
    logical :: use_shear_switch = .false. !< Balsara's switch on the artificial viscosity (&numerics sph_viscosity_switch)
    real(rk), allocatable :: switch(:)    !< (n+images) the switch's factor of the step
    !> (n+images) axisymmetric: the radial weights 2 pi r (m) and the sums
    !> sum_j m_j dW_ij/dr (kg/m3) of the forces, then of the rates
    real(rk), allocatable :: w(:), gr(:)
    real(rk), allocatable :: v_prev(:,:), v_pre(:,:)   !< (3,n) m/s: v(n-1/2), and v(n+1/2) before the contact pass
    real(rk), allocatable :: x_start(:,:) !< (3,n+images) m: x(n), for the rates after the contact pass
    integer, allocatable :: pairs(:,:), cell_start(:), order(:), cand(:)
    integer :: n_pairs = 0
    !> mirror images across the symmetry planes (in the arrays after the
    !> particles, n+1..n+n_ghosts, for one step): whose image, and across
    !> which planes (bit k: plane k)
    integer :: n_ghosts = 0
    integer, allocatable :: ghost_of(:), ghost_planes(:)
  end type

contains

  !> Room for at least n particles (kept contents; capacity doubles).
  subroutine particles_reserve(pt, n)
    type(particles_t), intent(inout) :: pt
    integer, intent(in) :: n
    integer :: cap
    if (allocated(pt%m)) then
      if (size(pt%m) >= n) return
    end if
    cap = max(n, 64)
    if (allocated(pt%m)) cap = max(cap, 2*size(pt%m))
    call grow2(pt%x, 3, cap); call grow2(pt%v, 3, cap); call grow2(pt%acc, 3, cap); call grow2(pt%v_prev, 3, cap)
    call grow2(pt%v_pre, 3, cap); call grow2(pt%x_start, 3, cap); call grow2(pt%s, 6, cap); call grow2(pt%grad, 9, cap)
    call grow2(pt%r_art, 6, cap); call grow1(pt%art_eps, cap); call grow1(pt%switch, cap)
    call grow1(pt%w, cap); call grow1(pt%gr, cap)
    call grow1(pt%hard, cap); call grow1(pt%soft, cap); call grow1(pt%damage, cap); call growl(pt%strong, cap)
    call grow1(pt%m, cap); call grow1(pt%rho, cap); call grow1(pt%e, cap); call grow1(pt%p, cap)
    call grow1(pt%c, cap); call grow1(pt%h, cap); call grow1(pt%temp, cap); call grow1(pt%eps_p, cap)
    call grow1(pt%drho, cap); call grow1(pt%dheat, cap); call grow1(pt%vsig, cap)
    call growi(pt%mat, cap); call growi(pt%part, cap); call growi(pt%elem, cap)
    call growi(pt%order, cap); call growi(pt%cell_start, 2*cap + 2)
    ! (the pair search's cells' fill pointers: up to 2 cells a particle)
    call growi(pt%cand, 2*cap + 2)
    call growi(pt%ghost_of, cap); call growi(pt%ghost_planes, cap)
  contains
    subroutine grow2(a, rows, c)
      real(rk), allocatable, intent(inout) :: a(:,:)
      integer, intent(in) :: rows, c
      real(rk), allocatable :: t(:,:)
      allocate(t(rows,c))
      t = 0
      if (allocated(a)) t(:,1:size(a,2)) = a
      call move_alloc(t, a)
    end subroutine
    subroutine grow1(a, c)
      real(rk), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: c
      real(rk), allocatable :: t(:)
      allocate(t(c))
      t = 0
      if (allocated(a)) t(1:size(a)) = a
      call move_alloc(t, a)
    end subroutine
    subroutine growl(a, c)
      logical, allocatable, intent(inout) :: a(:)
      integer, intent(in) :: c
      logical, allocatable :: t(:)
      allocate(t(c))
      t = .false.
      if (allocated(a)) t(1:size(a)) = a
      call move_alloc(t, a)
    end subroutine
    subroutine growi(a, c)
      integer, allocatable, intent(inout) :: a(:)
      integer, intent(in) :: c
      integer, allocatable :: t(:)
      allocate(t(c))
      t = 0
      if (allocated(a)) t(1:size(a)) = a
      call move_alloc(t, a)
    end subroutine
  end subroutine

  !> Room for at least np pairs (contents not kept: the pairs are found
  !> again each step).
  subroutine particles_pair_room(pt, np)
    type(particles_t), intent(inout) :: pt
    integer, intent(in) :: np
    if (allocated(pt%pairs)) then
      if (size(pt%pairs, 2) >= np) return
      deallocate(pt%pairs, pt%visc)
    end if
    allocate(pt%pairs(2, max(np, 1024)), pt%visc(max(np, 1024)))
  end subroutine
end module udar_particle_model
