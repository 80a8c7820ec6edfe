// The ladder of four-bar loops that `tests/large.rs` and `mbd-bench/stack` build (included by
// both, so that the stack figures are of the tested mechanism).

/// A hanging ladder of `$n` four-bar loops: `$n` + 1 rungs 0.4 m wide, a left rail of `$n`
/// links 0.3 m long pinned between them, massless 0.3 m links on the right; the top rung held
/// by a pin and a link to ground. Started sheared, every rail link 0.2 rad from hanging (the
/// top rung's angle 1e-4 rad off, so that assembly takes Newton steps). `$extra`: statements
/// before the bodies (`joint_coordinates;`).
macro_rules! ladder {
    ($(#[$doc:meta])* $name:ident, $n:tt $(, $extra:ident)?) => {
        mechanism! {
            $(#[$doc])*
            pub $name {
                $($extra;)?
                gravity [0.0, -9.81];
                body r[0] { mass: 1.0, inertia: 0.013333333333333334, at: [0.2, 0.0, 1e-4] }
                for k in 1..=$n {
                    body r[k] { mass: 1.0, inertia: 0.013333333333333334, at: [0.2 + 0.3 * k * sin(0.2), -0.3 * k * cos(0.2), 0.0] }
                }
                for k in 0..$n {
                    body a[k] {
                        mass: 0.5,
                        inertia: 0.00375,
                        at: [(0.3 * k + 0.15) * sin(0.2), -(0.3 * k + 0.15) * cos(0.2), 0.2 - PI / 2.0]
                    }
                    revolute r[k][-0.2, 0.0] ~ a[k][-0.15, 0.0];
                    revolute a[k][0.15, 0.0] ~ r[k + 1][-0.2, 0.0];
                    revolute_revolute r[k][0.2, 0.0] ~ r[k + 1][0.2, 0.0] { length: 0.3 };
                }
                revolute ground[0.0, 0.0] ~ r[0][-0.2, 0.0];
                revolute_revolute ground[0.4, 0.3] ~ r[0][0.2, 0.0] { length: 0.3 };
            }
        }
    };
}
