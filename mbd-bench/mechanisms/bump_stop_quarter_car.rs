// Issue 39's case (B), a suspension hitting a 1e6 N/m bump stop: the `bump` example's quarter
// car (a 250 kg chassis and a 35 kg wheel on vertical slides, a 2e4 N/m, 1500 N·s/m coil-over,
// a 2e5 N/m point-follower tyre) at 20 m/s over a 10 cm bump at t = 1 s, with its bump stop made
// linear at 1e6 N/m (Hunt–Crossley damping δ · 2e4 N·s/m² δ̇): the wheel closes the 4.7 cm
// of travel to the stop, compresses it and leaves the road. The stop and the tyre are
// unilateral: each start and end is located by the simulation. 2 s from rest on the flat road.
mbd::mechanism! {
    /// A quarter car over a 10 cm bump into a 1e6 N/m bump stop (issue 39, case B).
    pub BumpStopQuarterCar {
        params { speed: 20.0, height: 0.1, length: 0.5 }
        gravity [0.0, -9.81];
        body chassis { mass: 250.0, inertia: 10.0, at: [0.0, 0.71, 0.0] }
        body wheel { mass: 35.0, inertia: 1.0, at: [0.0, 0.29, 0.0] }
        translational ground[0.0, 0.0] along [0.0, 1.0] ~ chassis[0.0, 0.0] along [0.0, 1.0];
        translational chassis[0.0, 0.0] along [0.0, 1.0] ~ wheel[0.0, 0.0] along [0.0, 1.0];
        spring shock: chassis[0.0, 0.0] ~ wheel[0.0, 0.0] { k: 2.0e4, length: 0.55, c: 1500.0 };
        contact bump_stop: wheel[0.0, 0.1] ~ chassis[0.0, -0.28] along [0.0, -1.0] { k: 1.0e6, exponent: 1.0, c: 2.0e4 };
        tyre road: wheel[0.0, 0.0] ~ ground[0.0, 0.0] {
            radius: 0.3, k: 2.0e5, c: 200.0,
            road: height * sin(PI * clamp(speed * t - 20.0, 0.0, length) / length)^2
        };
    }
}
