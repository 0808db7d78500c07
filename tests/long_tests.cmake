# The discovered tests that take 10 s or more on one core (ctest -j1, measured): labelled `long`, left
# out by `scripts/test --quick`. Included by CTest after the discovered tests and their properties.
foreach(name
    Walls.IsphCubicCavityRe100ConvergesToTheReference DamBreak.FrontFollowsMartinMoyceIn3D
    Walls.IsphCavityRe1000StaysInsideAndApproachesGhia
    Walls.IsphCavityRe1000WithThePrescribedWallVelocityInTheSourceStaysInside Beltrami.IsphConvergesInH
    Walls.IsphCavityWithSymmetricLidCornersMatchesGhia Convergence.ObservedOrderInH
    Convergence.IsphErrorApproachesALimitAsDtFalls Walls.WcsphCavityRe100MatchesGhiaAndKeepsItsVolume
    Scene.CylinderArrayDragMatchesSanganiAcrivos Walls.IsphCavityRe100MatchesGhia
    Restart.Isph3DFreeSurfaceMatchesUninterruptedRunExactly MovingBodies.IsphCouetteTorqueMatchesTheory
    MovingBodies.IsphViscousAddedMassAndDampingMatchUnsteadyStokes
    Restart.WcsphWallBoundingMatchesUninterruptedRunExactly)
  set_tests_properties(${name} PROPERTIES LABELS "case;long")
endforeach()
