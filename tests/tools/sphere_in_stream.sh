# Shared by the restart tests: the body of a scene with one sphere of the
# pack file $1 in an 8 mm box, a 2 mm/s stream entering at x min and leaving
# through a pressure face at x max (penalization, mu = 1e-2 Pa s), writing
# quietly into directory $2. Source this file; the caller adds the
# simulation control (and coupling, DEM) subsections.
sphere_in_stream() { # grain_file directory
  cat <<PRM
subsection mesh
  set lower corner = -4e-3, -4e-3, -4e-3
  set upper corner = 4e-3, 4e-3, 4e-3
  set cells per diameter = 3
end
subsection grains
  set source = file
  set file = $1
end
subsection fluid
  set density = 1000
  set viscosity = 1e-2
  set theta = 1e6
  set solid model = penalization
end
subsection fluid solver
  set linear tolerance = 1e-12
end
subsection boundary conditions
  subsection x min
    set type = velocity
    set velocity = 2e-3, 0, 0
  end
  subsection x max
    set type = pressure
  end
end
subsection output
  set directory = $2
  set verbosity = quiet
end
PRM
}
