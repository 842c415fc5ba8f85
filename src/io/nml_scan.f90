!> Lexical scan of a namelist deck into its groups and assignments.
!>
!> gfortran's own namelist errors do not say where a deck is wrong (a bad value,
!> a misspelled group and a missing '/' all end as "End of file"), so before any
!> READ the deck text is split here into groups "&name ... /" and assignments
!> "variable = value", each with its line number. The values are not
!> interpreted: udar_deck reads them with real namelist READs and uses this
!> scan to say which line and which variable a failure belongs to.
!>
!> Understood: quoted strings ('...' and "...", quotes doubled inside) that may
!> contain / ! = &; comments from '!' to the end of the line; values spread over
!> several lines; subscripted names such as velocity(3) or velocity(1:2).
!> Reported as issues: text outside any group, a group without its closing '/',
!> a string without its closing quote, text inside a group that is not part of
!> an assignment.
!>
!> A file (not a string) may include others: a line   include 'file'   (as
!> Fortran's INCLUDE line; the name relative to the including file's folder)
!> is replaced by that file's lines, up to max_include_depth deep. The scan's
!> line numbers count the joined text; nml_location gives a line's own file
!> and line, for messages. A file that cannot be read is an issue at its
!> include line.
module udar_nml_scan
  use udar_strings, only: nml_lower => to_lower, itoa, replace, shorten, is_letter, is_digit
  use udar_file_kind, only: not_regular_file
  implicit none
  private
  public :: nml_assign_t, nml_group_t, nml_issue_t, nml_scan_t
  public :: nml_scan_file, nml_scan_string, nml_lower, nml_location

  character(len=*), parameter :: lf = achar(10)
  integer, parameter :: snippet_len = 40   !< longest piece of deck text quoted in an issue
  ! A deck has tens of groups and assignments. Past these counts the file is
  ! not a deck (a mesh given by mistake, a binary file): the scan stops, so
  ! that it neither prints thousands of lines nor takes minutes.
  integer, parameter :: max_issues = 20, max_groups = 200, max_assigns = 2000
  integer, parameter :: max_include_depth = 8, path_len = 1024

  !> One "variable = value" inside a group.
  type :: nml_assign_t
    character(len=:), allocatable :: name   !< lower case, blanks removed, with subscript: 'velocity(3)'
    character(len=:), allocatable :: base   !< lower case, without subscript: 'velocity'
    character(len=:), allocatable :: value  !< as written; comments dropped, lines joined, blanks collapsed
    integer :: line = 0                     !< line of the variable name
    logical :: ok = .true.                  !< false when the scan found a problem in the value
  end type

  !> One "&name ... /" group instance.
  type :: nml_group_t
    character(len=:), allocatable :: name   !< lower case, without '&'
    integer :: start_line = 0
    integer :: end_line = 0
    logical :: terminated = .true.          !< false when the closing '/' is missing
    logical :: clean = .true.               !< false when an issue was reported inside the group
    character(len=:), allocatable :: raw    !< the text from '&' to '/' as written (LF between lines)
    character(len=:), allocatable :: body   !< between the name and '/': comments dropped, on one line
    integer :: n_assign = 0
    type(nml_assign_t), allocatable :: assigns(:)
  end type

  !> A problem found by the scan.
  type :: nml_issue_t
    integer :: line = 0
    integer :: group = 0                    !< index into groups(:), 0 when outside any group
    character(len=:), allocatable :: text   !< what is wrong (no file/line prefix)
  end type

  type :: nml_scan_t
    integer :: n_groups = 0
    type(nml_group_t), allocatable :: groups(:)
    integer :: n_issues = 0
    type(nml_issue_t), allocatable :: issues(:)
    logical :: stopped = .false.            !< a limit was reached: the rest is not scanned
    integer :: n_assigns = 0                !< in all groups
    !> where each line of the scanned text comes from (files with includes;
    !> empty for a string): files(line_file(k)), its line line_orig(k)
    character(len=path_len), allocatable :: files(:)
    integer, allocatable :: line_file(:), line_orig(:)
  end type

contains

  !> Read the whole file, with the files it includes, and scan it. ios /= 0
  !> (with iomsg) if the file itself cannot be read.
  subroutine nml_scan_file(path, scan, ios, iomsg)
    character(len=*), intent(in) :: path
    type(nml_scan_t), intent(out) :: scan
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: iomsg
    character(len=:), allocatable :: buf, text
    character(len=path_len), allocatable :: files(:)
    integer, allocatable :: line_file(:), line_orig(:), bad_line(:)
    type(nml_issue_t), allocatable :: bad(:)
    integer :: k, n_text, n_lines

    call read_text(path, buf, ios, iomsg)
    if (ios /= 0) return
    if (.not. has_include(buf)) then
      ! no includes: the text as it is (a mesh given as a deck stays fast)
      call nml_scan_string(buf, scan)
      return
    end if
    allocate(files(1), bad(0), bad_line(0))
    allocate(character(len=len(buf) + 1024) :: text)
    allocate(line_file(1024), line_orig(1024))
    n_text = 0
    n_lines = 0
    files(1) = path
    call join_includes(buf, 1, 0)
    call nml_scan_string(text(1:n_text), scan)
    call move_alloc(files, scan%files)
    scan%line_file = line_file(1:n_lines)
    scan%line_orig = line_orig(1:n_lines)
    do k = 1, size(bad)
      call add_issue(scan, bad_line(k), 0, bad(k)%text)
    end do

  contains

    !> Append the lines of buf (file number f, at include depth depth) to
    !> text, each include line replaced by its file's lines.
    recursive subroutine join_includes(buf, f, depth)
      character(len=*), intent(in) :: buf
      integer, intent(in) :: f, depth
      character(len=:), allocatable :: name, inc, sub, why
      integer :: i, e, line, ios2
      character(len=256) :: msg2
      i = 1
      line = 0
      do while (i <= len(buf))
        e = line_end(buf, i)
        line = line + 1
        name = include_name(buf(i:e-1))
        if (len(name) == 0) then
          call add_line(buf(i:e-1), f, line)
        else
          ! the include line itself stays (a blank line), so messages about it have a place
          call add_line('', f, line)
          inc = name
          if (inc(1:1) /= '/') inc = folder_of(trim(files(f)))//inc
          why = ''
          if (depth >= max_include_depth) then
            why = 'includes nested more than '//itoa(max_include_depth)//' deep (does a file include itself?)'
          else
            msg2 = ''
            call read_text(inc, sub, ios2, msg2)
            if (ios2 /= 0) why = "cannot read '"//inc//"' (a relative name is taken from the including file's "// &
                                 'folder): '//trim(msg2)
          end if
          if (len(why) > 0) then
            bad = [bad, nml_issue_t(0, 0, "include '"//name//"': "//why)]
            bad_line = [bad_line, n_lines]
          else
            files = [character(len=path_len) :: files, inc]
            call join_includes(sub, size(files), depth + 1)
          end if
        end if
        i = e + 1
      end do
    end subroutine join_includes

    !> One line onto the joined text and its map (both grow by doubling).
    subroutine add_line(s, f, line)
      character(len=*), intent(in) :: s
      integer, intent(in) :: f, line
      character(len=:), allocatable :: bigger
      integer, allocatable :: more(:)
      if (n_text + len(s) + 1 > len(text)) then
        allocate(character(len=2*(n_text + len(s) + 1)) :: bigger)
        bigger(1:n_text) = text(1:n_text)
        call move_alloc(bigger, text)
      end if
      text(n_text+1:n_text+len(s)) = s
      text(n_text+len(s)+1:n_text+len(s)+1) = lf
      n_text = n_text + len(s) + 1
      if (n_lines == size(line_file)) then
        allocate(more(2*n_lines)); more(1:n_lines) = line_file; call move_alloc(more, line_file)
        allocate(more(2*n_lines)); more(1:n_lines) = line_orig; call move_alloc(more, line_orig)
      end if
      n_lines = n_lines + 1
      line_file(n_lines) = f
      line_orig(n_lines) = line
    end subroutine add_line
  end subroutine nml_scan_file

  !> The whole of a regular file.
  subroutine read_text(path, buf, ios, iomsg)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: buf
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: iomsg
    character(len=:), allocatable :: what
    integer :: u, sz
    ! a FIFO or a terminal would block the OPEN or the READ forever
    what = not_regular_file(path)
    if (len(what) > 0) then
      ios = 1
      iomsg = 'it is '//what//', not a regular file'
      return
    end if
    ! stream access reads the file byte for byte, whatever its line lengths
    open(newunit=u, file=path, access='stream', form='unformatted', status='old', &
         action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) return
    inquire(unit=u, size=sz)
    if (sz < 0) sz = 0
    allocate(character(len=sz) :: buf)
    if (sz > 0) read(u, iostat=ios, iomsg=iomsg) buf
    close(u)
  end subroutine read_text

  !> The position of the LF that ends the line starting at i (len + 1 for
  !> a last line without one).
  pure integer function line_end(buf, i) result(e)
    character(len=*), intent(in) :: buf
    integer, intent(in) :: i
    e = index(buf(i:), lf)
    if (e == 0) then
      e = len(buf) + 1
    else
      e = i + e - 1
    end if
  end function line_end

  !> Whether some line of buf starts (after blanks) with 'include' in any
  !> case: only then are lines looked at one by one.
  pure logical function has_include(buf)
    character(len=*), intent(in) :: buf
    integer :: i, e, k
    has_include = .false.
    i = 1
    do while (i <= len(buf))
      e = line_end(buf, i)
      k = verify(buf(i:e-1), ' '//achar(9)//achar(13))
      if (k > 0 .and. i + k + 5 <= e - 1) then
        if (nml_lower(buf(i+k-1:i+k+5)) == 'include') then
          has_include = .true.
          return
        end if
      end if
      i = e + 1
    end do
  end function has_include

  !> The file name of an include line ("include 'name'", any case, blanks
  !> and a trailing comment allowed), '' for any other line.
  function include_name(s) result(name)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: name
    character(len=:), allocatable :: t
    character :: q
    integer :: i, j
    name = ''
    i = verify(s, ' '//achar(9)//achar(13))
    if (i == 0 .or. len(s) - i < 8) return
    if (nml_lower(s(i:i+6)) /= 'include') return
    t = adjustl(replace(replace(s, achar(9), ' '), achar(13), ' '))
    if (len(t) < 9) return
    if (nml_lower(t(1:7)) /= 'include' .or. t(8:8) /= ' ') return
    t = adjustl(t(8:))
    q = t(1:1)
    if (q /= "'" .and. q /= '"') return
    j = index(t(2:), q)
    if (j < 2) return
    i = verify(t(j+2:), ' ')
    if (i > 0) then
      if (t(j+1+i:j+1+i) /= '!') return
    end if
    name = t(2:j)
  end function include_name

  !> The folder of a file name with its '/' ('' for a bare name).
  pure function folder_of(path) result(dir)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: dir
    dir = path(1:index(path, '/', back=.true.))
  end function folder_of

  !> "file:line" of line k of the scanned text: its own file and line when
  !> the scan joined included files, else default_path:k.
  function nml_location(scan, k, default_path) result(where)
    type(nml_scan_t), intent(in) :: scan
    integer, intent(in) :: k
    character(len=*), intent(in) :: default_path
    character(len=:), allocatable :: where
    where = default_path//':'//itoa(k)
    if (.not. allocated(scan%line_file)) return
    if (k < 1 .or. k > size(scan%line_file)) return
    where = trim(scan%files(scan%line_file(k)))//':'//itoa(scan%line_orig(k))
  end function nml_location

  !> Scan deck text (lines separated by LF; CR and TAB count as blanks).
  subroutine nml_scan_string(text, scan)
    character(len=*), intent(in) :: text
    type(nml_scan_t), intent(out) :: scan
    character(len=:), allocatable :: cl
    character(len=:), allocatable :: msg
    integer :: i, j, e, n, line, last_end_line
    character :: c

    allocate(scan%groups(0), scan%issues(0))
    n = len(text)
    ! cl is the working copy: comments inside groups get blanked in it, so
    ! that bodies and values can be cut out of it directly
    cl = text
    do i = 1, n
      if (cl(i:i) == achar(9) .or. cl(i:i) == achar(13)) cl(i:i) = ' '
    end do

    i = 1
    line = 1
    last_end_line = 0
    do while (i <= n)
      if (scan%stopped) exit
      c = cl(i:i)
      if (c == lf) then
        line = line + 1
        i = i + 1
      else if (c == ' ') then
        i = i + 1
      else if (c == '!') then
        i = eol(cl, i)
      else if (c == '&') then
        j = name_end(cl, i + 1)
        if (scan%n_groups >= max_groups) then
          call stop_scan(scan, line, 0, 'more than '//itoa(max_groups)//' groups')
        else if (j == i + 1) then
          call add_issue(scan, line, 0, "'&' must be followed by a group name, e.g. &run")
          i = eol(cl, i)
        else
          call scan_group(text, cl, i, j, line, scan)
          last_end_line = line
        end if
      else
        e = eol(cl, i)
        ! the snippet stops at a comment (a '!' in quotes here is rare enough)
        j = index(cl(i:e-1), '!')
        if (j == 0) j = e - i + 1
        msg = "text outside any group: '"//shorten(trim(cl(i:i+j-2)), snippet_len)//"'"
        if (last_end_line == line) then
          ! typical cause: an unquoted value containing '/', which ends the group early
          msg = msg//" (a '/' ends a group: should a value before it be in quotes?)"
        end if
        call add_issue(scan, line, 0, msg)
        i = e
      end if
    end do
  end subroutine nml_scan_string

  !> Scan one group starting at '&' at position i (name ends before j).
  !> On return i is after the closing '/', or at the '&' of the next group,
  !> or past the end of the text; line is the current line.
  subroutine scan_group(text, cl, i, j, line, scan)
    character(len=*), intent(in) :: text
    character(len=*), intent(inout) :: cl
    integer, intent(inout) :: i
    integer, intent(in) :: j
    integer, intent(inout) :: line
    type(nml_scan_t), intent(inout) :: scan
    integer :: n, g, start, body_start, vstart, k, m, p, e, last_tok_line, last_unexp_line, na
    character :: c
    character(len=:), allocatable :: gname, msg
    logical :: unterminated      ! a string without its closing quote was reported

    n = len(cl)
    start = i
    gname = nml_lower(cl(i+1:j-1))
    call add_group(scan, gname, line)
    g = scan%n_groups
    body_start = j
    vstart = 0
    last_tok_line = line
    last_unexp_line = 0
    unterminated = .false.
    i = j
    do while (i <= n)
      if (scan%stopped) then
        call close_value(i - 1)
        call finish_open(i - 1)
        return
      end if
      c = cl(i:i)
      if (c == lf) then
        line = line + 1
        i = i + 1
      else if (c == ' ' .or. c == ',') then
        i = i + 1
      else if (c == '!') then
        e = eol(cl, i)
        cl(i:e-1) = ' '
        i = e
      else if (c == '/') then
        call close_value(i - 1)
        scan%groups(g)%end_line = line
        scan%groups(g)%raw = text(start:i)
        scan%groups(g)%body = collapse(cl(body_start:i-1))
        i = i + 1
        return
      else if (c == '&') then
        ! a new group begins although this one was never closed
        call close_value(i - 1)
        k = name_end(cl, i + 1)
        ! after an unterminated string the '/' was most likely inside it: no second message
        if (.not. unterminated) call add_issue(scan, scan%groups(g)%start_line, g, '&'//gname//' (line '// &
             itoa(scan%groups(g)%start_line)//") has no closing '/' before &"// &
             nml_lower(cl(i+1:k-1))//' at line '//itoa(line))
        call finish_open(i - 1)
        return
      else if (c == "'" .or. c == '"') then
        if (vstart == 0) call unexpected(i)
        k = close_quote(cl, i)
        last_tok_line = line
        if (k == 0) then
          e = eol(cl, i)
          msg = ': add the closing '//c//' (a string ends on the line where it starts; a '//c// &
                ' inside it is written twice)'
          na = scan%groups(g)%n_assign
          if (na > 0 .and. vstart > 0) then
            ! name the variable: "&output: directory = 'out / : unterminated ..."
            msg = '&'//gname//': '//scan%groups(g)%assigns(na)%name//' = '// &
                  shorten(trim(collapse(cl(vstart:e-1))), snippet_len)//' : unterminated string'//msg
          else
            msg = 'unterminated string '//shorten(trim(cl(i:e-1)), snippet_len)//msg
          end if
          call add_issue(scan, line, g, msg)
          unterminated = .true.
          scan%groups(g)%clean = .false.
          if (na > 0) scan%groups(g)%assigns(na)%ok = .false.
          ! drop the rest of the line: it is part of the broken string
          cl(i:e-1) = ' '
          i = e
        else
          ! the string as written: a TAB in it must reach the checks (as a
          ! control character in a file name), not become a blank
          cl(i:k) = text(i:k)
          i = k + 1
        end if
      else if (is_letter(c)) then
        ! an identifier followed by an optional (subscript) and '=' starts an
        ! assignment; otherwise it is part of a value (e.g. T, F, NaN)
        k = name_end(cl, i)
        e = k
        m = skip_blanks(cl, k, .false.)
        if (m <= n) then
          if (cl(m:m) == '(') then
            ! subscript: the closing ')' must be on the same line
            p = index(cl(m:eol(cl, m)-1), ')')
            if (p > 0) then
              m = m + p
            else
              m = n + 1
            end if
          end if
        end if
        ! the '=' may be on the next line, as namelist input allows
        if (m <= n) m = skip_blanks(cl, m, .true.)
        last_tok_line = line
        if (m <= n) then
          if (cl(m:m) == '=') then
            call close_value(i - 1)
            if (scan%n_assigns >= max_assigns) then
              call stop_scan(scan, line, g, 'more than '//itoa(max_assigns)//' assignments')
              cycle
            end if
            scan%n_assigns = scan%n_assigns + 1
            call add_assign(scan%groups(g), nml_lower(no_blanks(cl(i:m-1))), &
                            nml_lower(cl(i:e-1)), line)
            line = line + count_lf(cl(i:m))
            vstart = m + 1
            i = m + 1
            cycle
          end if
        end if
        if (vstart == 0) call unexpected(i)
        i = e
      else
        if (vstart == 0) call unexpected(i)
        last_tok_line = line
        i = i + 1
      end if
    end do
    ! end of text inside the group
    call close_value(n)
    if (.not. unterminated) call add_issue(scan, scan%groups(g)%start_line, g, '&'//gname//' (line '// &
         itoa(scan%groups(g)%start_line)//") has no closing '/' (the end of the file was reached)")
    call finish_open(n)

  contains

    !> The value of the current assignment runs from vstart to last.
    subroutine close_value(last)
      integer, intent(in) :: last
      integer :: na
      character(len=:), allocatable :: v
      na = scan%groups(g)%n_assign
      if (na == 0 .or. vstart == 0) return
      v = collapse(cl(vstart:last))
      ! a trailing separator is not part of the value
      do while (len(v) > 0)
        if (v(len(v):len(v)) /= ',' .and. v(len(v):len(v)) /= ' ') exit
        v = v(1:len(v)-1)
      end do
      scan%groups(g)%assigns(na)%value = v
      vstart = 0
    end subroutine close_value

    !> Close a group that has no '/': it ends at position last.
    subroutine finish_open(last)
      integer, intent(in) :: last
      scan%groups(g)%terminated = .false.
      scan%groups(g)%clean = .false.
      scan%groups(g)%end_line = last_tok_line
      scan%groups(g)%raw = trim_trailing(text(start:last))
      scan%groups(g)%body = collapse(cl(body_start:last))
    end subroutine finish_open

    !> Text inside a group that does not belong to an assignment (once per line).
    subroutine unexpected(at)
      integer, intent(in) :: at
      integer :: t
      character(len=:), allocatable :: tok, msg
      scan%groups(g)%clean = .false.
      if (last_unexp_line == line) return
      last_unexp_line = line
      t = at
      do while (t <= n)
        if (index(' ,/!'//lf, cl(t:t)) > 0) exit
        t = t + 1
      end do
      tok = cl(at:t-1)
      msg = "unexpected text '"//shorten(tok, snippet_len)//"' in &"//gname// &
            ": expected 'variable = value'"
      if (is_letter(tok(1:1))) msg = msg//" (missing '=' after '"//shorten(tok, snippet_len)//"'?)"
      call add_issue(scan, line, g, msg)
    end subroutine unexpected

  end subroutine scan_group

  ! ---------------------------------------------------------------- helpers

  !> Position of the LF ending the line that contains position i (len+1 if none).
  pure integer function eol(s, i)
    character(len=*), intent(in) :: s
    integer, intent(in) :: i
    eol = index(s(i:), lf)
    if (eol == 0) then
      eol = len(s) + 1
    else
      eol = i + eol - 1
    end if
  end function eol

  !> First position at or after i that is not a blank (nor a line end, if
  !> cross_lines).
  pure integer function skip_blanks(s, i, cross_lines)
    character(len=*), intent(in) :: s
    integer, intent(in) :: i
    logical, intent(in) :: cross_lines
    skip_blanks = i
    do while (skip_blanks <= len(s))
      if (s(skip_blanks:skip_blanks) /= ' ' .and. &
          .not. (cross_lines .and. s(skip_blanks:skip_blanks) == lf)) exit
      skip_blanks = skip_blanks + 1
    end do
  end function skip_blanks

  pure integer function count_lf(s)
    character(len=*), intent(in) :: s
    integer :: i
    count_lf = 0
    do i = 1, len(s)
      if (s(i:i) == lf) count_lf = count_lf + 1
    end do
  end function count_lf

  !> Position of the quote closing the string opened at i on the same line, 0 if none.
  !> A doubled quote inside the string stands for one quote character.
  pure integer function close_quote(s, i)
    character(len=*), intent(in) :: s
    integer, intent(in) :: i
    integer :: k
    character :: q
    q = s(i:i)
    k = i + 1
    close_quote = 0
    do while (k <= len(s))
      if (s(k:k) == lf) return
      if (s(k:k) == q) then
        if (k < len(s)) then
          if (s(k+1:k+1) == q) then
            k = k + 2
            cycle
          end if
        end if
        close_quote = k
        return
      end if
      k = k + 1
    end do
  end function close_quote

  !> Join lines and squeeze runs of blanks outside quotes; trim both ends.
  function collapse(s) result(r)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: r
    character(len=len(s)) :: buf
    character :: c, q
    integer :: i, k
    logical :: prev_blank

    k = 0
    q = ' '
    prev_blank = .true.
    do i = 1, len(s)
      c = s(i:i)
      if (c == lf) c = ' '
      if (q /= ' ') then
        k = k + 1
        buf(k:k) = c
        if (c == q) q = ' '   ! a doubled quote re-opens on the next character
        prev_blank = .false.
      else if (c == ' ') then
        if (.not. prev_blank) then
          k = k + 1
          buf(k:k) = ' '
        end if
        prev_blank = .true.
      else
        if (c == "'" .or. c == '"') q = c
        k = k + 1
        buf(k:k) = c
        prev_blank = .false.
      end if
    end do
    r = trim(buf(1:k))
  end function collapse

  pure function no_blanks(s) result(r)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: r
    r = replace(replace(s, ' ', ''), lf, '')
  end function no_blanks

  !> Remove trailing blanks and line breaks.
  pure function trim_trailing(s) result(r)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: r
    integer :: k
    k = len(s)
    do while (k > 0)
      if (s(k:k) /= ' ' .and. s(k:k) /= lf .and. s(k:k) /= achar(13)) exit
      k = k - 1
    end do
    r = s(1:k)
  end function trim_trailing

  pure logical function is_name_char(c)
    character, intent(in) :: c
    is_name_char = is_letter(c) .or. is_digit(c) .or. c == '_'
  end function is_name_char

  !> First position at or after i that is not part of a name (len+1 if none).
  pure integer function name_end(s, i)
    character(len=*), intent(in) :: s
    integer, intent(in) :: i
    name_end = i
    do while (name_end <= len(s))
      if (.not. is_name_char(s(name_end:name_end))) exit
      name_end = name_end + 1
    end do
  end function name_end

  ! The lists grow by one item at a time: a deck has tens of groups and
  ! assignments, so copying on each append costs nothing that matters.

  subroutine add_group(scan, name, line)
    type(nml_scan_t), intent(inout) :: scan
    character(len=*), intent(in) :: name
    integer, intent(in) :: line
    type(nml_assign_t) :: no_assigns(0)
    scan%groups = [scan%groups, nml_group_t(name=name, start_line=line, end_line=line, &
                                            raw='', body='', assigns=no_assigns)]
    scan%n_groups = scan%n_groups + 1
  end subroutine add_group

  subroutine add_assign(gr, name, base, line)
    type(nml_group_t), intent(inout) :: gr
    character(len=*), intent(in) :: name, base
    integer, intent(in) :: line
    gr%assigns = [gr%assigns, nml_assign_t(name=name, base=base, value='', line=line)]
    gr%n_assign = gr%n_assign + 1
  end subroutine add_assign

  subroutine add_issue(scan, line, group, text)
    type(nml_scan_t), intent(inout) :: scan
    integer, intent(in) :: line, group
    character(len=*), intent(in) :: text
    if (scan%stopped) return
    if (scan%n_issues >= max_issues) then
      call stop_scan(scan, line, group, 'more than '//itoa(max_issues)//' problems')
      return
    end if
    scan%issues = [scan%issues, nml_issue_t(line=line, group=group, text=text)]
    scan%n_issues = scan%n_issues + 1
  end subroutine add_issue

  !> Give up on a file that cannot be a deck: one last issue, no further scan.
  subroutine stop_scan(scan, line, group, why)
    type(nml_scan_t), intent(inout) :: scan
    integer, intent(in) :: line, group
    character(len=*), intent(in) :: why
    if (scan%stopped) return
    scan%issues = [scan%issues, nml_issue_t(line=line, group=group, text=why// &
                   ': the rest of the file is not read (is it a namelist deck?)')]
    scan%n_issues = scan%n_issues + 1
    scan%stopped = .true.
  end subroutine stop_scan

end module udar_nml_scan
