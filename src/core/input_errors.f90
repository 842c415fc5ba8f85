!> A growing list of input problems (deck, mesh, ...), collected so that every
!> mistake in the input is reported at once instead of one per run.
!> Generic: messages are complete sentences formatted by whoever finds them,
!> conventionally "file:line: where: what is wrong".
module udar_input_errors
  implicit none
  private
  public :: input_errors_t, input_errors_report

  type :: message_t
    character(len=:), allocatable :: text
  end type

  type :: input_errors_t
    private
    type(message_t), allocatable :: msgs(:)
    integer :: n = 0
  contains
    procedure :: add => errors_add
    procedure :: count => errors_count
    procedure :: message => errors_message
    procedure :: contains_text => errors_contains_text
    procedure :: clear => errors_clear
  end type

contains

  !> Append one message (leading and trailing blanks removed).
  subroutine errors_add(self, msg)
    class(input_errors_t), intent(inout) :: self
    character(len=*), intent(in) :: msg
    type(message_t), allocatable :: tmp(:)
    integer :: i

    if (.not. allocated(self%msgs)) allocate(self%msgs(8))
    if (self%n == size(self%msgs)) then
      ! grow geometrically; move_alloc keeps the already allocated strings
      allocate(tmp(2*size(self%msgs)))
      do i = 1, self%n
        call move_alloc(self%msgs(i)%text, tmp(i)%text)
      end do
      call move_alloc(tmp, self%msgs)
    end if
    self%n = self%n + 1
    self%msgs(self%n)%text = trim(adjustl(msg))
  end subroutine errors_add

  !> Number of messages collected so far.
  pure integer function errors_count(self)
    class(input_errors_t), intent(in) :: self
    errors_count = self%n
  end function errors_count

  !> Message i (1..count()); empty string when out of range.
  function errors_message(self, i) result(text)
    class(input_errors_t), intent(in) :: self
    integer, intent(in) :: i
    character(len=:), allocatable :: text
    if (i >= 1 .and. i <= self%n) then
      text = self%msgs(i)%text
    else
      text = ''
    end if
  end function errors_message

  !> True if some message contains all of the given fragments (case-sensitive).
  !> Meant for tests and for drivers that react to a particular problem.
  logical function errors_contains_text(self, frag1, frag2, frag3) result(found)
    class(input_errors_t), intent(in) :: self
    character(len=*), intent(in) :: frag1
    character(len=*), intent(in), optional :: frag2, frag3
    integer :: i
    logical :: ok
    found = .false.
    do i = 1, self%n
      ok = index(self%msgs(i)%text, frag1) > 0
      if (present(frag2)) ok = ok .and. index(self%msgs(i)%text, frag2) > 0
      if (present(frag3)) ok = ok .and. index(self%msgs(i)%text, frag3) > 0
      if (ok) then
        found = .true.
        return
      end if
    end do
  end function errors_contains_text

  !> Forget all messages.
  subroutine errors_clear(self)
    class(input_errors_t), intent(inout) :: self
    if (allocated(self%msgs)) deallocate(self%msgs)
    self%n = 0
  end subroutine errors_clear

  !> Write every message on its own line to unit, then a count line.
  subroutine input_errors_report(errs, unit)
    type(input_errors_t), intent(in) :: errs
    integer, intent(in) :: unit
    integer :: i
    character(len=16) :: num

    do i = 1, errs%n
      write(unit, '(a)') errs%msgs(i)%text
    end do
    write(num, '(i0)') errs%n
    if (errs%n == 1) then
      write(unit, '(a)') '1 input error.'
    else
      write(unit, '(a)') trim(num)//' input errors.'
    end if
  end subroutine input_errors_report

end module udar_input_errors
