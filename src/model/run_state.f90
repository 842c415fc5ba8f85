!> The run's own state besides the mesh fields: what a checkpoint must hold,
!> with the domain, for a restart to continue bitwise as if never stopped.
module udar_run_state
  use udar_kinds, only: rk, i8
  use udar_exact_sum, only: exact_limbs
  implicit none
  private

  type, public :: run_state_t
    real(rk) :: t = 0, dt_old = 0, dt_stable = 0   !< s: time, last step, stable step of the current state
    real(rk) :: dt0 = 0                           !< s, stable step at the start (erosion by time step)
    integer :: cycle = 0
    real(rk) :: e0 = 0, e_ref = 0                 !< J: initial energy and the error scale
    real(rk) :: ke_peak = 0                       !< J, largest kinetic energy so far (&run end_kinetic_fraction)
    real(rk) :: t_next_field = 0, t_next_hist = 0, t_next_checkpoint = 0   !< s
    integer :: field_steps = 0                    !< committed field output steps
    integer :: checkpoints_written = 0            !< picks the next rotating checkpoint slot
    integer :: history_rows = 0                   !< rows of the history file (header not counted)
    integer(i8) :: wall_work(0:exact_limbs) = 0   !< J, exact global wall work (udar_exact_sum)
    integer(i8) :: contact_work(0:exact_limbs) = 0 !< J, exact global work of the contact impulses
    integer(i8) :: model_hash = 0, mesh_hash = 0  !< what the checkpoint belongs to
  end type
end module udar_run_state
