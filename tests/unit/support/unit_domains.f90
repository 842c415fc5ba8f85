!> Domains the unit tests build from the regression meshes, the way a run
!> does (deck, gmsh mesh, the mesh domain), before partitioning.
module unit_domains
  use udar_config, only: config_t
  use udar_input_errors, only: input_errors_t
  use udar_deck, only: deck_read
  use udar_gmsh, only: gmsh_mesh_t, gmsh_read
  use udar_domain, only: domain_t
  use udar_setup, only: build_domain
  implicit none
  private
  public :: elastic_bar_mesh_domain, elastic_bar_2d_mesh_domain

contains

  !> The mesh domain of the elastic-bar regression deck (4800 tetrahedra),
  !> with its deck; unit_dir is tests/unit.
  subroutine elastic_bar_mesh_domain(unit_dir, cfg, glob)
    character(len=*), intent(in) :: unit_dir
    type(config_t), intent(out) :: cfg
    type(domain_t), intent(out) :: glob
    call regression_mesh_domain(unit_dir//'/../regression/elastic_bar/elastic_bar.nml', 3, cfg, glob)
  end subroutine

  !> The mesh domain of the axisymmetric elastic-bar regression deck (2000
  !> triangles, radius 5 mm, length 100 mm), with its deck.
  subroutine elastic_bar_2d_mesh_domain(unit_dir, cfg, glob)
    character(len=*), intent(in) :: unit_dir
    type(config_t), intent(out) :: cfg
    type(domain_t), intent(out) :: glob
    call regression_mesh_domain(unit_dir//'/../regression/elastic_bar_2d/elastic_bar_2d.nml', 2, cfg, glob)
  end subroutine

  !> A regression deck, its mesh (of dimension dim) and the mesh domain.
  subroutine regression_mesh_domain(deck, dim, cfg, glob)
    character(len=*), intent(in) :: deck
    integer, intent(in) :: dim
    type(config_t), intent(out) :: cfg
    type(domain_t), intent(out) :: glob
    type(input_errors_t) :: errs
    type(gmsh_mesh_t) :: mesh
    character(len=:), allocatable :: msg
    logical :: ok
    call deck_read(deck, cfg, errs)
    call gmsh_read(trim(cfg%mesh%file), cfg%mesh%scale, mesh, ok, msg, dim=dim)
    if (errs%count() /= 0 .or. .not. ok) error stop 'cannot read the regression deck '//deck//' and its mesh'
    call build_domain(cfg, mesh, glob, errs)
  end subroutine
end module unit_domains
