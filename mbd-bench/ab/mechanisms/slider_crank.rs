// The driven slider-crank of `examples/slider_crank.rs` as it stood at 810f85d (the pin on the
// slider written inline, not as the named point `slider.pin` HEAD's example declares): the same
// DSL text compiles on both sides, so both generate from identical input.
mbd::mechanism! {
    /// Slider-crank driven at constant speed ω (Nikravesh, ch. 7).
    pub SliderCrank {
        params { omega: 2.0 * PI, r: 0.1, l: 0.3 }
        body crank  { mass: 1.0, inertia: 0.002, at: [0.05, 0.0, 0.0] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.25, 0.0, 0.0] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.4, 0.0, 0.0] }
        point crank.O = [-r / 2.0, 0.0];
        point crank.A = [r / 2.0, 0.0];
        point rod.A = [-l / 2.0, 0.0];
        point rod.B = [l / 2.0, 0.0];
        revolute ground[0.0, 0.0] ~ crank.O;
        revolute crank.A ~ rod.A;
        revolute rod.B ~ slider[0.0, 0.0];
        translational slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        drive crank.phi = omega * t;
    }
}
