//! Two mechanisms as a user documents them: a planar slider-crank with named points, a labelled
//! joint, a user constraint and a spring, and a spatial slider-crank.
use mbd::prelude::*;

mechanism! {
    /// Planar slider-crank with a return spring.
    pub SliderCrank {
        params { r: 0.1, l: 0.3, k: 50.0 }
        gravity [0.0, -9.81];
        body crank  { mass: 1.0, inertia: 0.002, at: [0.0433, 0.025, 0.5236] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.2345, 0.025, -0.1674] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.3823, 0.0, 0.0] }
        point crank.A = [r / 2.0, 0.0];
        point rod.B = [l / 2.0, 0.0];
        revolute pin: ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank.A ~ rod[-l / 2.0, 0.0];
        revolute rod.B ~ slider[0.0, 0.0];
        constraint level: slider.y = 0.0;
        constraint upright: slider.phi = 0.0;
        spring return_spring: slider[0.0, 0.0] ~ ground[0.6, 0.0] { k: k, length: 0.2 };
    }
}

mechanism! {
    /// Offset spatial slider-crank, driven.
    pub SpatialSliderCrank {
        spatial;
        params { a: 0.05, len: 0.20, ey: 0.02, ez: 0.03, omega: 20.0 * PI }
        gravity [0.0, 0.0, -9.81];
        body crank { mass: 2.0, inertia: [2.0e-3, 2.0e-3, 3.0e-3] }
        body slider { mass: 0.8, inertia: [1.0e-4, 2.0e-4, 2.0e-4], at: [0.25, ey, ez] }
        revolute crankshaft: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ crank[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0];
        translational guide: ground[0.0, ey, ez] along [1.0, 0.0, 0.0] ~ slider[0.0, 0.0, 0.0] along [1.0, 0.0, 0.0];
        distance rod: crank[a, 0.0, 0.0] ~ slider[0.0, 0.0, 0.0] { length: len };
        drive motor: crankshaft.angle = omega * t;
    }
}
