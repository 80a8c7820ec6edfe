// The slider-crank of `examples/slider_crank.rs` without its driver: free under gravity, with
// the crank released from 30° at rest (9 coordinates, 8 constraint rows, 1 degree of freedom) —
// the forward-dynamics benchmark's small mechanism.
mbd::mechanism! {
    /// Free slider-crank under gravity (benchmark).
    pub FreeSliderCrank {
        params { r: 0.1, l: 0.3 }
        gravity [0.0, -9.81];
        body crank  { mass: 1.0, inertia: 0.002, at: [0.0433, 0.025, 0.5236] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.2345, 0.025, -0.1674] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.3823, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ slider[0.0, 0.0];
        translational slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
    }
}
