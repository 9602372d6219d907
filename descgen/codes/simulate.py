"""Codes of ``descgen simulate``: MuJoCo as a consumer of the URDF.

One constant per code, named as the code, in code order; raise one as ``CODE.finding(...)``
(descgen/codes/registry.py)."""

from __future__ import annotations

from descgen.codes.registry import Stage

declare = Stage("simulate")


SIM001 = declare(
    "SIM001",
    "mujoco-mass-below-minimum",
    "error",
    "MuJoCo refuses a moving body whose mass or a principal inertia is below mjMINVAL (1e-15): "
    "zero, negative or all-zero inertia.",
    """MuJoCo will not load the robot at all ("mass and inertia of moving bodies must be larger than
      mjMINVAL"), and urdfdom accepts it, so the problem appears only in simulation. Give every moving
      link a positive mass and a positive-definite inertia tensor (or inertia from its collision shape).""",
)

SIM002 = declare(
    "SIM002",
    "mujoco-inertia-triangle",
    "error",
    "MuJoCo refuses a body whose principal moments of inertia break the triangle inequality (A + B >= C).",
    """No rigid body has such moments; MuJoCo refuses the model, and with balanceinertia it silently
      replaces all three by their mean, a different body. Recompute the tensor (a unit slip in one
      entry is the usual cause).""",
)

SIM003 = declare(
    "SIM003",
    "mujoco-refused",
    "error",
    "MuJoCo refused the model for another reason (its message is quoted).",
    """A description that MuJoCo cannot compile cannot be simulated there. The quoted message names
      the element; fix the description, or report a bug if the URDF is valid.""",
)

SIM004 = declare(
    "SIM004",
    "mujoco-fused-fixed-links",
    "info",
    "Links on fixed joints are merged into their parent body (MuJoCo's fusestatic default for URDF).",
    """The merged links are no bodies in MuJoCo: they cannot carry sensors, sites or contacts of their
      own, and their names vanish from the model. Expected for tool and sensor frames; add
      <mujoco><compiler fusestatic="false"/></mujoco> to the URDF if a consumer needs them.""",
)

SIM005 = declare(
    "SIM005",
    "mujoco-visuals-dropped",
    "info",
    "The visuals are discarded; only collision shapes exist in MuJoCo (discardvisual default for URDF).",
    """What is drawn in MuJoCo is the collision geometry, so a robot that looks right in RViz may look
      different there. A link with visuals but no collision is invisible and intangible in MuJoCo.""",
)

SIM006 = declare(
    "SIM006",
    "mujoco-mass-from-geometry",
    "warning",
    "A link without <inertial> gets mass and inertia from its collision shapes at 1000 kg/m^3.",
    """urdfdom and RViz treat the link as massless, MuJoCo silently gives it the mass of water of its
      volume, so the two consumers simulate different robots. Give the link an <inertial>.""",
)

SIM007 = declare(
    "SIM007",
    "mujoco-unlimited-joint",
    "warning",
    "A revolute or prismatic joint with lower > upper or only one bound becomes unlimited in MuJoCo.",
    """MuJoCo makes such a joint silently unlimited (sdformat swaps the bounds instead), so the joint
      can move anywhere in simulation. Write lower <= upper, both bounds.""",
)

SIM008 = declare(
    "SIM008",
    "mujoco-mesh-unavailable",
    "error",
    "A collision mesh cannot be handed to MuJoCo (not found inside the named folders, a COLLADA file "
    "that cannot be read, or a format neither MuJoCo nor descgen reads); the shape is left out.",
    """MuJoCo opens mesh filenames as plain paths and reads STL, OBJ and MSH only (descgen converts a
      readable COLLADA mesh to STL for it); without the shape the link neither collides nor draws
      there. Give --package-path, or convert the mesh.""",
)

SIM009 = declare(
    "SIM009",
    "mujoco-unavailable",
    "error",
    "The mujoco Python package is not installed.",
    """descgen simulate compiles and runs the robot with MuJoCo, an optional dependency. Install it with
      pip install 'descgen[sim]' (or pip install 'mujoco>=3').""",
)

SIM010 = declare(
    "SIM010",
    "sim-not-finite",
    "error",
    "The gravity run produced NaN or infinite positions or velocities.",
    """The simulation blew up: typically an inertia far too small for its link, a huge actuator gain,
      or no damping. The joint named is where it showed first; check its link's mass and inertia.""",
)

SIM011 = declare(
    "SIM011",
    "sim-unstable",
    "error",
    "MuJoCo warned during the gravity run (bad acceleration, contact or constraint overflow).",
    """MuJoCo resets the state on a bad acceleration (mjWARN_BADQACC), so a run that looks calm may have
      blown up and restarted. Check masses, inertias, gains and damping.""",
)

SIM012 = declare(
    "SIM012",
    "sim-joint-left-pose",
    "error",
    "A joint held by a PD controller at the pose drifted beyond its tolerance under gravity, or was "
    "still moving at the end.",
    """A joint that its effort limit cannot hold against gravity (mass too large, centre of mass too far
      out) sags or falls in simulation although RViz shows the pose. Check the masses carried by the joint
      and its effort limit.""",
)

SIM013 = declare(
    "SIM013",
    "sim-base-tipped",
    "error",
    "The mobile base, free on a ground plane, tilted beyond the limit or left the floor.",
    """A centre of mass outside the support of wheels and casters tips the robot over; a description
      that looks right in RViz falls over in simulation. Check the base and arm masses and where their
      centres of mass are.""",
)

SIM014 = declare(
    "SIM014",
    "sim-unknown-pose",
    "error",
    "--pose names no known pose (spec known_poses) and no SRDF group state.",
    """The run holds the joints at the named pose; an unknown name is a typo. The message lists the
      pose names there are.""",
)

SIM015 = declare(
    "SIM015",
    "sim-contacts-excluded",
    "info",
    "Bodies of the robot touch at the pose; their contacts are left out of the gravity run.",
    """MuJoCo never filters contacts with the world body (a fixed root) and only filters parent and
      child, so shapes that overlap at rest would push the joints away from the pose. The run excludes
      them, as an SRDF's disabled collisions would; a consumer needs the same <exclude> pairs.""",
)

SIM016 = declare(
    "SIM016",
    "sim-nothing-to-hold",
    "error",
    "The robot has no movable joint with one degree of freedom and is not on a free base: the gravity "
    "run proves nothing.",
    """Nothing moves, so nothing can sag or tip. Use --base floor for a mobile base, or simulate a
      description that has joints.""",
)

SIM017 = declare(
    "SIM017",
    "sim-too-large",
    "error",
    "The robot is too large to simulate: more than 2,000 links, more than 500 degrees of freedom, or "
    "more mass-matrix work over the run than the bound; nothing is compiled (exit 2).",
    """MuJoCo's compiler and the servos' pseudo-inverse grow with the cube of the degrees of freedom, and
      each step factorises the mass matrix: a 10,000-link chain would run for hours. The bounds keep a run
      within about 15 s; simulate fewer --seconds, or a smaller description.""",
)
