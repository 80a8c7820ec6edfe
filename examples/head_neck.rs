//! Nikravesh's project 15.4, the head and neck in a rear impact (whiplash), posed as a seat
//! designer asks it: how far does the head rotate back on the torso, what loads does the upper
//! neck carry, and how much does the head restraint's distance behind the head (the backset)
//! change them?
//!
//! The model (planar, in the occupant's side view, x forward and y up; SI units; every number's
//! source in `SOURCES`): the torso, held to the seat at T1, follows the sled's pulse (a half-sine
//! of 16 km/h); on it the neck as a chain of the seven cervical vertebrae C7 … C1, one revolute
//! joint per level with a rotational spring and damper (the disc and ligaments) that stiffens at
//! the end of the level's range, and the head on C1 at the occipital condyles (OC). The head
//! restraint is a contact on the seat, a plane `backset` behind the back of the head. The
//! occupant sits at rest in the passive neck's static posture before the pulse.
//!
//! **The checks** (each written by hand from the model's data, not from the generated equations;
//! the last takes the simulated accelerations and checks the loads against them):
//!
//! - the static posture against the chain's moment balance written by hand (at each level, the
//!   spring's torque equals the moment of the weight above it), solved by Newton's method on the
//!   exact trigonometry;
//! - the response to a pulse a ten-thousandth as strong, without gravity, against the
//!   small-angle model of the chain written by hand (M φ̈ + C φ̇ + K φ = −b ẍ_sled, the absolute
//!   angles φ of the eight bodies), integrated by hand with RK4;
//! - the upper neck's loads (the shear and axial force at OC and the moment about it) against
//!   Newton–Euler of the head by hand, from its acceleration, its weight and the restraint's
//!   force, at every sample.
//!
//! Run: `cargo run --release --example head_neck`
use mbd::prelude::*;

mechanism! {
    /// The head and neck of a seated occupant in a rear impact (Nikravesh's project 15.4): the
    /// torso follows the sled; seven cervical vertebrae and the head, with a rotational spring
    /// and damper at each level; the head restraint a contact on the seat.
    pub HeadNeck {
        // dv: the sled's change of speed (m/s); peak: its largest acceleration (m/s²);
        // k_disc, c_disc: each level's stiffness (N·m/rad) and damping (N·m·s/rad); range: each
        // level's range before it stiffens (rad), k_stop: the stiffening (N·m/rad²);
        // rest_x: the restraint's plane, from T1 (m); k_rest, c_rest: its foam (N/m, N·s/m²).
        params {
            dv: 16.0 / 3.6, peak: 8.0 * 9.81,
            k_disc: 1.5 / deg(1.0), c_disc: 0.3, range: deg(9.0), k_stop: 2.0e4,
            rest_x: -0.15, k_rest: 3.0e4, c_rest: 1.5e4
        }
        gravity [0.0, -9.81];
        // The half-sine pulse: its duration, and the time into it. Both kinks at its end take,
        // at the instant itself, the branch before it (a tie takes the first argument's), so the
        // driver's velocity there is the pulse's, not the sum of both sides'.
        let pulse = PI * dv / (2.0 * peak);
        let into = min(t, pulse);
        // The torso with T1 at its origin, on the seat: it slides with the sled.
        body t1 { mass: 20.0, inertia: 0.5, at: [0.0, 0.0, 0.0] }
        translational seat: ground[0.0, 0.0] along [1.0, 0.0] ~ t1[0.0, 0.0] along [1.0, 0.0];
        drive sled: t1.x = peak * pulse / PI * (into - pulse / PI * sin(PI * into / pulse)) + dv * max(0.0, t - pulse);
        // C7 … C1, 18 mm a level, each with its centre of mass midway between its joints.
        for n in 1..=7 {
            body c[n] { mass: 0.15, inertia: 2.4e-4, at: [0.0, 0.018 * (7 - n) + 0.009, 0.0] }
        }
        body head { mass: 4.5, inertia: 0.0232, at: [0.02, 0.166, 0.0] }
        revolute t1_c7: t1[0.0, 0.0] ~ c[7][0.0, -0.009];
        for n in 1..7 {
            revolute disc[n]: c[n + 1][0.0, 0.009] ~ c[n][0.0, -0.009];
        }
        revolute oc: c[1][0.0, 0.009] ~ head[-0.02, -0.04];
        // Each level's spring and damper; θ = upper − lower, extension positive.
        rotational_spring level[7]: t1 ~ c[7] {
            k: k_disc, c: c_disc,
            torque: k_stop * (max(c[7].phi - t1.phi - range, 0.0)^2 - max(t1.phi - c[7].phi - range, 0.0)^2)
        };
        for n in 1..7 {
            rotational_spring level[n]: c[n + 1] ~ c[n] {
                k: k_disc, c: c_disc,
                torque: k_stop * (max(c[n].phi - c[n + 1].phi - range, 0.0)^2 - max(c[n + 1].phi - c[n].phi - range, 0.0)^2)
            };
        }
        rotational_spring level[0]: c[1] ~ head {
            k: k_disc, c: c_disc,
            torque: k_stop * (max(head.phi - c[1].phi - range, 0.0)^2 - max(c[1].phi - head.phi - range, 0.0)^2)
        };
        // The back of the skull, 0.1 m from the head's centre of mass: level with it and 30° and
        // 60° above (the rearmost as the head turns back); the condyles; the restraint's plane.
        point head.back = [-0.1, 0.0];
        point head.crown = [-0.0866, 0.05];
        point head.top = [-0.05, 0.0866];
        point head.condyles = [-0.02, -0.04];
        point t1.restraint = [rest_x, 0.166];
        contact restraint: head.back ~ t1.restraint along [1.0, 0.0] { k: k_rest, c: c_rest };
        contact restraint_crown: head.crown ~ t1.restraint along [1.0, 0.0] { k: k_rest, c: c_rest };
        contact restraint_top: head.top ~ t1.restraint along [1.0, 0.0] { k: k_rest, c: c_rest };
        scene Unrestrained without restraint, restraint_crown, restraint_top;
        scene Weightless without gravity, restraint, restraint_crown, restraint_top;
    }
}

/// Where the numbers come from (assumptions are marked so).
pub const SOURCES: [(&str, &str); 10] = [
    (
        "the sled's pulse: a half-sine, 16 km/h, peak 8 g (89.0 ms)",
        "the GDV/ETH/Autoliv seat test's Δv of 16 km/h and its representative pulse of 6–8 g (Langwieder and Hell, Traffic Injury Prevention 3(2), 2002); the half-sine's shape an assumption",
    ),
    ("the torso at T1 moving with the sled", "assumption: a rigid seat back, the torso held to it (no ramping, no seat-back rotation)"),
    ("the torso 20 kg, 0.5 kg·m²", "assumption: driven, it changes only the seat's force on it"),
    ("each level's stiffness 1.5 N·m/deg (85.9 N·m/rad)", "Voo, Pintar, Yoganandan and Liu, J. Biomech. Eng. 120(6), 1998: the dynamic bending stiffness of cervical joints, 1.50 N·m/deg mean"),
    ("each level's damping 0.3 N·m·s/rad", "assumption"),
    (
        "each level's range 9° before it stiffens (k_stop δ², 2·10⁴ N·m/rad²)",
        "assumption: eight levels of 9° give the head 72° of extension on the torso, about an adult's range; the stiffening a stand-in for the ligaments and facets",
    ),
    ("head 4.5 kg, J = 0.0232 kg·m² (radius of gyration 7.18 cm)", "Beier et al., 1980: heads of 3.66–5.76 kg, mean radius of gyration 7.18 cm about the lateral axis"),
    ("the head's centre of mass 2 cm ahead of and 4 cm above the occipital condyles; its back 0.1 m behind it", "assumption"),
    ("vertebrae 18 mm a level (a neck of 126 mm from T1 to OC), 0.15 kg and 2.4·10⁻⁴ kg·m² each with their tissue", "assumption"),
    ("head restraint foam: 3·10⁴ N/m, Hunt–Crossley damping 1.5·10⁴ N·s/m²", "assumption"),
];

/// Each level's spacing (m), the vertebrae's and head's masses (kg) and inertias (kg·m²), the
/// centres of mass from each body's lower joint (m), as in the mechanism: for the hand models.
const LEVEL: f64 = 0.018;
const MASSES: [f64; 8] = [0.15, 0.15, 0.15, 0.15, 0.15, 0.15, 0.15, 4.5];
const INERTIAS: [f64; 8] = [2.4e-4, 2.4e-4, 2.4e-4, 2.4e-4, 2.4e-4, 2.4e-4, 2.4e-4, 0.0232];
const CENTRES: [[f64; 2]; 8] =
    [[0.0, 0.009], [0.0, 0.009], [0.0, 0.009], [0.0, 0.009], [0.0, 0.009], [0.0, 0.009], [0.0, 0.009], [0.02, 0.04]];
/// The backsets a designer compares (m); `None`: no head restraint.
pub const BACKSETS: [Option<f64>; 4] = [None, Some(0.10), Some(0.07), Some(0.04)];

/// One backset's answers. Angles in degrees, times in s, forces in N, moments in N·m.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone, Copy)]
pub struct Case {
    pub backset: Option<f64>,
    /// The head's largest rotation back on the torso from the seated posture, and when.
    pub rotation: f64,
    pub rotation_at: f64,
    /// NICmax (m²/s²), the largest of 0.2 a_rel + v_rel² over the first 150 ms, and when.
    pub nic: f64,
    pub nic_at: f64,
    /// The upper neck's (at OC, in the head's frame) largest shear, axial force and extension
    /// moment (moment about OC).
    pub shear: f64,
    pub axial: f64,
    pub moment: f64,
    /// When the head first touches the restraint (the located instant), and the restraint's
    /// largest force.
    pub contact_at: Option<f64>,
    pub contact_force: f64,
    /// The head's largest forward acceleration (g).
    pub head_acceleration: f64,
    /// Largest |OC force − Newton–Euler by hand| (N) and |moment about OC − the level's spring
    /// law by hand| (N·m) over the samples.
    pub force_error: f64,
    pub moment_error: f64,
}

/// What the run measured.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone)]
pub struct Report {
    /// The seated posture: the head's angle (deg, flexion negative), and the largest |body angle
    /// − the hand statics'| (rad).
    pub posture: f64,
    pub posture_error: f64,
    /// The weak pulse without gravity: the head's largest rotation (rad) and the largest
    /// |angle − small-angle model| over all bodies and samples, relative to it.
    pub small_rotation: f64,
    pub small_error: f64,
    pub cases: Vec<Case>,
}

/// The sled's acceleration (m/s²) at t: the mechanism's half-sine, by hand.
fn sled_acceleration(dv: f64, peak: f64, t: f64) -> f64 {
    let pulse = PI * dv / (2.0 * peak);
    if t < pulse {
        peak * (PI * t / pulse).sin()
    } else {
        0.0
    }
}

/// The torque (N·m) a level's spring and damper exert against θ = upper − lower: the mechanism's
/// `rotational_spring`, by hand.
fn level_torque(m: &HeadNeck, theta: f64, rate: f64) -> f64 {
    let stop = |x: f64| x.max(0.0).powi(2);
    m.k_disc * theta + m.c_disc * rate + m.k_stop * (stop(theta - m.range) - stop(-theta - m.range))
}

/// x = A⁻¹ b by Gaussian elimination with partial pivoting (A is small and regular here).
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for col in 0..n {
        let pivot = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs())).unwrap_or(col);
        a.swap(col, pivot);
        b.swap(col, pivot);
        let (above, below) = a.split_at_mut(col + 1);
        let pivot_row = &above[col];
        for (offset, row) in below.iter_mut().enumerate() {
            let f = row[col] / pivot_row[col];
            row[col..].iter_mut().zip(&pivot_row[col..]).for_each(|(x, p)| *x -= f * p);
            b[col + 1 + offset] -= f * b[col];
        }
    }
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        let sum: f64 = (row + 1..n).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - sum) / a[row][row];
    }
    x
}

/// The seated posture by hand: the absolute angles φ of C7 … C1 and the head at which, at every
/// level j, the spring's torque τ(φ_j − φ_{j−1}) (φ_0 = 0, the torso) balances the moment of the
/// weight above it about the level's joint, τ_j = −g Σ_{b ≥ j} m_b (x_b − x_j); Newton's method
/// with a difference Jacobian, from upright.
fn posture_by_hand(m: &HeadNeck) -> [f64; 8] {
    let residual = |phi: &[f64; 8]| -> Vec<f64> {
        // Each body's lower joint and centre of mass.
        let mut joint = [0.0; 9];
        let mut centre = [0.0; 8];
        for b in 0..8 {
            let (s, c) = phi[b].sin_cos();
            centre[b] = joint[b] + CENTRES[b][0] * c - CENTRES[b][1] * s;
            joint[b + 1] = joint[b] - LEVEL * s;
        }
        (0..8)
            .map(|j| {
                let below = if j == 0 { 0.0 } else { phi[j - 1] };
                let weight: f64 = (j..8).map(|b| MASSES[b] * (centre[b] - joint[j])).sum();
                level_torque(m, phi[j] - below, 0.0) + 9.81 * weight
            })
            .collect()
    };
    let mut phi = [0.0; 8];
    for _ in 0..50 {
        let r = residual(&phi);
        let jacobian: Vec<Vec<f64>> = (0..8)
            .map(|i| {
                (0..8)
                    .map(|k| {
                        let mut p = phi;
                        p[k] += 1e-7;
                        (residual(&p)[i] - r[i]) / 1e-7
                    })
                    .collect()
            })
            .collect();
        let step = solve(jacobian, r.iter().map(|x| -x).collect());
        phi.iter_mut().zip(&step).for_each(|(p, s)| *p += s);
        if step.iter().all(|s| s.abs() < 1e-15) {
            break;
        }
    }
    phi
}

/// The small-angle model of the chain without gravity, by hand, in the absolute angles φ of C7 …
/// C1 and the head: a body's centre of mass moves x_s − Σ_{a<i} L φ_a − c_y φ_i forward and c_x φ_i
/// up, so M_ab = Σ_i m_i (X_ia X_ib + Y_ia Y_ib) + J_a δ_ab and the sled drives it with
/// −Σ_i m_i X_ia ẍ_s; the springs and dampers are K and C on the relative angles. Integrated by
/// RK4 (100 steps a sample, the pulse's end a step's end); the angles at each of `times`.
fn small_angle_model(m: &HeadNeck, times: &[f64]) -> Vec<[f64; 8]> {
    let x = |i: usize, a: usize| {
        if a < i {
            -LEVEL
        } else if a == i {
            -CENTRES[i][1]
        } else {
            0.0
        }
    };
    let y = |i: usize, a: usize| if a == i { CENTRES[i][0] } else { 0.0 };
    let mass: Vec<Vec<f64>> = (0..8)
        .map(|a| {
            (0..8)
                .map(|b| {
                    (0..8).map(|i| MASSES[i] * (x(i, a) * x(i, b) + y(i, a) * y(i, b))).sum::<f64>()
                        + if a == b { INERTIAS[a] } else { 0.0 }
                })
                .collect()
        })
        .collect();
    let drive: Vec<f64> = (0..8).map(|a| -(0..8).map(|i| MASSES[i] * x(i, a)).sum::<f64>()).collect();
    // Level j joins body j − 1 (the torso for j = 0) and body j.
    let levels = |phi: &[f64; 8], gain: f64| -> [f64; 8] {
        let mut torque = [0.0; 8];
        for j in 0..8 {
            let below = if j == 0 { 0.0 } else { phi[j - 1] };
            let tau = gain * (phi[j] - below);
            torque[j] -= tau;
            if j > 0 {
                torque[j - 1] += tau;
            }
        }
        torque
    };
    let rate = |t: f64, s: &[f64; 16]| -> [f64; 16] {
        let (phi, omega): ([f64; 8], [f64; 8]) = (core::array::from_fn(|k| s[k]), core::array::from_fn(|k| s[8 + k]));
        let (spring, damper) = (levels(&phi, m.k_disc), levels(&omega, m.c_disc));
        let a = sled_acceleration(m.dv, m.peak, t);
        let alpha = solve(mass.clone(), (0..8).map(|k| spring[k] + damper[k] + drive[k] * a).collect());
        core::array::from_fn(|k| if k < 8 { omega[k] } else { alpha[k - 8] })
    };
    let rk4 = |t: f64, s: &mut [f64; 16], h: f64| {
        let add = |s: &[f64; 16], k: &[f64; 16], f: f64| -> [f64; 16] { core::array::from_fn(|i| s[i] + f * k[i]) };
        let k1 = rate(t, s);
        let k2 = rate(t + h / 2.0, &add(s, &k1, h / 2.0));
        let k3 = rate(t + h / 2.0, &add(s, &k2, h / 2.0));
        let k4 = rate(t + h, &add(s, &k3, h));
        *s = core::array::from_fn(|i| s[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    };
    let pulse = PI * m.dv / (2.0 * m.peak);
    let (mut t, mut s) = (0.0, [0.0; 16]);
    let mut out = Vec::with_capacity(times.len());
    for &end in times {
        // Up to the pulse's end first, if it falls in this interval: the forcing has a kink there.
        for stop in [pulse, end] {
            if stop > t && stop <= end {
                let h = (stop - t) / 100.0;
                for _ in 0..100 {
                    rk4(t, &mut s, h);
                    t += h;
                }
                t = stop;
            }
        }
        out.push(core::array::from_fn(|k| s[k]));
    }
    out
}

/// The angles (rad) of C7 … C1 and the head in a state of any of the mechanism's scenes.
fn angles(q: &[f64; HeadNeck::NQ]) -> [f64; 8] {
    let bodies = [HeadNeck::C_7, HeadNeck::C_6, HeadNeck::C_5, HeadNeck::C_4, HeadNeck::C_3, HeadNeck::C_2, HeadNeck::C_1, HeadNeck::HEAD];
    core::array::from_fn(|b| bodies[b].phi(q))
}

/// The weak pulse without gravity against the small-angle model: (the head's largest rotation
/// (rad), the largest |angle − model| over all bodies and samples relative to it).
fn small_pulse() -> Result<(f64, f64), Box<dyn std::error::Error>> {
    let mut m = Weightless::default();
    m.dv *= 1e-4;
    m.peak *= 1e-4;
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut Weightless::workspace(), &mut q, 0.0)?;
    let times: Vec<f64> = (1..=300).map(|k| 0.001 * k as f64).collect();
    let mut simulated = Vec::with_capacity(times.len());
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-15));
    Simulation::new(&m, &mut dopri).start(0.0, &q, &[0.0; Weightless::NV]).times(&times).run(&mut Weightless::workspace(), |s| {
        // The pulse's end is a located event with a sample of its own: only the output times.
        if s.event.is_none() {
            simulated.push(angles(&s.point.q))
        }
    })?;
    let base = HeadNeck { dv: m.dv, peak: m.peak, ..HeadNeck::default() };
    let model = small_angle_model(&base, &times);
    let largest = simulated.iter().map(|a| a[7].abs()).fold(0.0, f64::max);
    let error = simulated.iter().zip(&model).flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs())).fold(0.0, f64::max);
    Ok((largest, error / largest))
}

/// What one run records at each sample, for the answers and the plots: (t, rotation in deg,
/// NIC in m²/s²).
type Trace = Vec<(f64, f64, f64)>;

/// The head restraint's force on the head (N, forward) by hand: each of the skull's three points
/// against the plane `rest_x` behind T1, Hunt–Crossley with exponent 1.
fn restraint_force(m: &HeadNeck, q: &[f64; HeadNeck::NQ], v: &[f64; HeadNeck::NV]) -> [(f64, [f64; 2]); 3] {
    let plane = HeadNeck::T1.position(q).x + m.rest_x;
    let speed = HeadNeck::T1.velocity(v).x;
    [m.head_back(), m.head_crown(), m.head_top()].map(|point| {
        let (at, at_v) = (point.position(q), point.velocity(q, v));
        let (depth, rate) = (plane - at.x, speed - at_v.x);
        (if depth > 0.0 { (depth * (m.k_rest + m.c_rest * rate)).max(0.0) } else { 0.0 }, [at.x, at.y])
    })
}

/// Newton–Euler of the head, by hand, from its motion and the restraint's forces `contacts`
/// (each with its point): the force the neck exerts at OC, F_OC = m (a − g) − Σ F_c (N, global),
/// and the moment it exerts about OC — from Euler about the centre of mass, I α = M + (r_OC − r_G)
/// × F_OC + Σ (r_c − r_G) × F_c, that is M = I α + (r_G − r_OC) × m (a − g) − Σ (r_c − r_OC) × F_c —
/// and the same moment by the top level's spring, damper and stiffening (N·m).
fn head_by_hand(
    m: &HeadNeck,
    q: &[f64; HeadNeck::NQ],
    v: &[f64; HeadNeck::NV],
    vd: &[f64; HeadNeck::NV],
    contacts: &[(f64, [f64; 2]); 3],
) -> ([f64; 2], f64, f64) {
    let (mass, inertia) = (MASSES[7], INERTIAS[7]);
    let (centre, accel) = (HeadNeck::HEAD.position(q), HeadNeck::HEAD.acceleration(vd));
    let inertial = [mass * accel.x, mass * (accel.y + 9.81)];
    let pushing: f64 = contacts.iter().map(|c| c.0).sum();
    let oc = m.head_condyles().position(q);
    let cross = |r: [f64; 2], f: [f64; 2]| r[0] * f[1] - r[1] * f[0];
    let about_oc: f64 = contacts.iter().map(|c| cross([c.1[0] - oc.x, c.1[1] - oc.y], [c.0, 0.0])).sum();
    let moment = inertia * HeadNeck::HEAD.alpha(vd) + cross([centre.x - oc.x, centre.y - oc.y], inertial) - about_oc;
    let theta = HeadNeck::HEAD.phi(q) - HeadNeck::C_1.phi(q);
    let spring = -level_torque(m, theta, HeadNeck::HEAD.omega(v) - HeadNeck::C_1.omega(v));
    ([inertial[0] - pushing, inertial[1]], moment, spring)
}

/// One backset from the seated posture `q0`: the answers, and the trace when `trace`.
fn case(backset: Option<f64>, q0: &[f64; HeadNeck::NQ], trace: bool) -> Result<(Case, Trace), Box<dyn std::error::Error>> {
    let back = HeadNeck::default().head_back().position(q0).x;
    // Without a restraint its plane is out of reach (and out of the scene `Unrestrained`).
    let m = HeadNeck { rest_x: back - backset.unwrap_or(10.0), ..HeadNeck::default() };
    let mut r = Case {
        backset,
        rotation: 0.0,
        rotation_at: 0.0,
        nic: 0.0,
        nic_at: 0.0,
        shear: 0.0,
        axial: 0.0,
        moment: 0.0,
        contact_at: None,
        contact_force: 0.0,
        head_acceleration: 0.0,
        force_error: 0.0,
        moment_error: 0.0,
    };
    let mut samples = Trace::new();
    let upright = HeadNeck::HEAD.phi(q0);
    let times: Vec<f64> = (1..=600).map(|k| 0.0005 * k as f64).collect();
    let mut record = |s: &mbd::Sample<f64, { HeadNeck::NQ }, { HeadNeck::NV }, { HeadNeck::NC }>| {
        let (q, v, vd, t) = (&s.point.q, &s.point.v, &s.point.vd, s.point.t);
        // The first located switch of a restraint's contact is the head's first touch (the
        // scene `Unrestrained` has none: its switches are the pulse's end).
        if let Some(mbd::EventHit::Switch(k)) = s.event {
            if backset.is_some() && HeadNeck::SWITCH_NAMES[k].starts_with("restraint") && r.contact_at.is_none() {
                r.contact_at = Some(t);
            }
            return;
        }
        let rotation = (HeadNeck::HEAD.phi(q) - upright).to_degrees();
        if rotation > r.rotation {
            (r.rotation, r.rotation_at) = (rotation, t);
        }
        let condyles = m.head_condyles();
        let (a_rel, v_rel) =
            (HeadNeck::T1.acceleration(vd).x - condyles.acceleration(q, v, vd).x, HeadNeck::T1.velocity(v).x - condyles.velocity(q, v).x);
        let nic = 0.2 * a_rel + v_rel * v_rel;
        if t <= 0.150 + 1e-12 && nic > r.nic {
            (r.nic, r.nic_at) = (nic, t);
        }
        r.head_acceleration = r.head_acceleration.max(HeadNeck::HEAD.acceleration(vd).x / 9.81);
        // The restraint, by hand; the upper neck by Newton–Euler of the head, by hand.
        let contacts = if backset.is_some() { restraint_force(&m, q, v) } else { [(0.0, [0.0; 2]); 3] };
        let pushing: f64 = contacts.iter().map(|c| c.0).sum();
        r.contact_force = r.contact_force.max(pushing);
        let (force, moment, spring) = head_by_hand(&m, q, v, vd, &contacts);
        r.moment_error = r.moment_error.max((moment - spring).abs());
        r.moment = r.moment.max(-spring);
        if let Some(on_head) = joint_reaction_at(&m, q, v, vd, t, &s.point.lambda, HeadNeck::OC).and_then(|j| j.on("head")) {
            r.force_error = r.force_error.max((on_head.force[0] - force[0]).hypot(on_head.force[1] - force[1]));
            let local = on_head.force_in_body_frame();
            r.shear = r.shear.max(local[0].abs());
            r.axial = r.axial.max(local[1].abs());
        }
        if trace {
            samples.push((t, rotation, nic));
        }
    };
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-9).with_atol(1e-12));
    let v0 = [0.0; HeadNeck::NV];
    match backset {
        Some(_) => Simulation::new(&m, &mut dopri).start(0.0, q0, &v0).times(&times).run(&mut HeadNeck::workspace(), |s| record(s))?,
        None => {
            let free = Unrestrained::default();
            Simulation::new(&free, &mut dopri).start(0.0, q0, &v0).times(&times).run(&mut Unrestrained::workspace(), |s| record(s))?
        }
    };
    Ok((r, samples))
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    // The seated posture: the passive neck at rest under the head's weight, before the pulse.
    let m = HeadNeck::default();
    let mut q0 = m.initial_positions();
    mbd::StaticSolver::default().solve(&m, &mut HeadNeck::workspace(), &mut q0, 0.0, &mut [0.0; HeadNeck::NC])?;
    let by_hand = posture_by_hand(&m);
    let posture_error = angles(&q0).iter().zip(&by_hand).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    let (small_rotation, small_error) = small_pulse()?;
    let mut cases = Vec::new();
    let mut traces = Vec::new();
    for backset in BACKSETS {
        let (c, trace) = case(backset, &q0, print)?;
        cases.push(c);
        traces.push(trace);
    }
    let r = Report { posture: HeadNeck::HEAD.phi(&q0).to_degrees(), posture_error, small_rotation, small_error, cases };
    if print {
        print_report(&m, &r, &traces)?;
    }
    Ok(r)
}

/// A backset's name: "no restraint" or "backset 70 mm".
fn label(backset: Option<f64>) -> String {
    backset.map_or("no restraint".to_string(), |b| format!("backset {:.0} mm", 1e3 * b))
}

/// The answers, the checks and the sources, and the designer's plots in target/showcase: the
/// head's rotation and NIC over time for each backset.
fn print_report(m: &HeadNeck, r: &Report, traces: &[Trace]) -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "Head and neck in a rear impact (Nikravesh's project 15.4): a {:.0} km/h half-sine of {:.0} g peak ({:.1} ms)",
        m.dv * 3.6,
        m.peak / 9.81,
        1e3 * PI * m.dv / (2.0 * m.peak)
    );
    println!(
        "seated posture: the head flexed {:.2}° under its weight (within {:.1e} rad of the hand statics)",
        -r.posture, r.posture_error
    );
    println!(
        "a pulse 1e-4 as strong, without gravity: the head turns {:.2e} rad, every body within {:.1e} of that from the small-angle model",
        r.small_rotation, r.small_error
    );
    println!(
        "{:<16} {:>10} {:>8} {:>10} {:>8} {:>9} {:>9} {:>11} {:>10} {:>11} {:>10}",
        "", "rotation", "at (ms)", "NIC m²/s²", "at (ms)", "shear N", "axial N", "moment N·m", "contact ms", "restraint N", "head a (g)"
    );
    for c in &r.cases {
        println!(
            "{:<16} {:>9.1}° {:>8.1} {:>10.1} {:>8.1} {:>9.0} {:>9.0} {:>11.1} {:>10} {:>11.0} {:>10.1}",
            label(c.backset),
            c.rotation,
            1e3 * c.rotation_at,
            c.nic,
            1e3 * c.nic_at,
            c.shear,
            c.axial,
            c.moment,
            c.contact_at.map_or("-".to_string(), |t| format!("{:.1}", 1e3 * t)),
            c.contact_force,
            c.head_acceleration
        );
    }
    let (force, moment) = r.cases.iter().fold((0.0, 0.0), |(f, n), c| (c.force_error.max(f), c.moment_error.max(n)));
    println!("the upper neck's loads within {force:.1e} N and {moment:.1e} N·m of Newton–Euler of the head by hand at every sample");
    for (what, source) in SOURCES {
        println!("  {what}: {source}");
    }
    let dir = std::path::Path::new("target/showcase");
    std::fs::create_dir_all(dir)?;
    let plot = |title: &str, axis: &str, pick: fn(&(f64, f64, f64)) -> f64, file: &str| {
        let mut plot = mbd::Plot::new(title).labels("time (ms)", axis);
        for (c, trace) in r.cases.iter().zip(traces) {
            plot = plot.series(label(c.backset), trace.iter().map(|p| (1e3 * p.0, pick(p))));
        }
        plot.write_svg(dir.join(file))
    };
    plot("Rear impact at 16 km/h: the head's rotation back on the torso", "rotation (deg)", |p| p.1, "head_neck_rotation.svg")?;
    plot("Rear impact at 16 km/h: the neck injury criterion NIC", "NIC (m²/s²)", |p| p.2, "head_neck_nic.svg")?;
    println!("plots → target/showcase/head_neck_rotation.svg, head_neck_nic.svg");
    Ok(())
}

/// The 70 mm backset over 250 ms, for the showcase's animation: 100 frames.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let base = HeadNeck::default();
    let mut q = base.initial_positions();
    mbd::StaticSolver::default().solve(&base, &mut HeadNeck::workspace(), &mut q, 0.0, &mut [0.0; HeadNeck::NC])?;
    let m = HeadNeck { rest_x: base.head_back().position(&q).x - 0.07, ..base };
    let mut animation =
        mbd::Animation::new::<HeadNeck>(&m.params()).title("Head and neck in a 16 km/h rear impact, head restraint 70 mm behind the head");
    let times: Vec<f64> = (0..=100).map(|k| 0.0025 * k as f64).collect();
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-9).with_atol(1e-12));
    Simulation::new(&m, &mut dopri).start(0.0, &q, &[0.0; HeadNeck::NV]).times(&times).run(&mut HeadNeck::workspace(), |s| {
        if s.event.is_none() {
            animation.frame(s.point.t, &s.point.q)
        }
    })?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("head_neck: {e}");
        std::process::exit(1);
    }
}
