//! Stage 4: symbolic equations → Rust.
//!
//! Each generated function is straight-line code over one set of outputs. Nodes of the graph
//! used more than once are bound once (`let v12 = ...;`) in topological order — common
//! subexpressions across all outputs of the function are computed once — and nodes used once
//! are written in place. `sin φ` and `cos φ` of one angle become one `sin_cos` call.

use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap, HashSet};

use proc_macro2::{Literal, Span, TokenStream};
use quote::{format_ident, quote};
use syn::Ident;

use crate::formulation::Formulation;
use crate::model::{Model, Scalar};
use crate::scalar::scalarize;
use crate::sym::{Cmp, Func, Graph, Id, Node, Var};

/// Operation counts of one emitted function (see `mbd_runtime::OpCount`).
#[derive(Clone, Copy, Default, Debug, PartialEq, Eq)]
pub struct Ops {
    pub add: u32,
    pub mul: u32,
    pub div: u32,
    pub call: u32,
}

impl Ops {
    /// All operations together.
    pub fn total(&self) -> u32 {
        self.add + self.mul + self.div + self.call
    }

    /// What one node costs written out (`Emitter::definition`): a negation is folded into its
    /// reader, x² and x³ are products, 1/x^k a division, a comparison an addition.
    fn of(node: Node) -> Ops {
        let (add, mul, div, call) = match node {
            Node::Const(_) | Node::Var(_) | Node::Neg(_) => (0, 0, 0, 0),
            Node::Add(..) | Node::Select(..) => (1, 0, 0, 0),
            Node::Mul(..) => (0, 1, 0, 0),
            Node::Div(..) => (0, 0, 1, 0),
            Node::PowI(_, 2) => (0, 1, 0, 0),
            Node::PowI(_, 3) => (0, 2, 0, 0),
            Node::PowI(_, -1) => (0, 0, 1, 0),
            Node::PowI(_, -2) => (0, 1, 1, 0),
            Node::PowI(_, -3) => (0, 2, 1, 0),
            Node::PowI(..) | Node::Pow(..) | Node::Call(..) | Node::Atan2(..) => (0, 0, 0, 1),
        };
        Ops { add, mul, div, call }
    }
}

impl std::ops::AddAssign for Ops {
    fn add_assign(&mut self, o: Ops) {
        self.add += o.add;
        self.mul += o.mul;
        self.div += o.div;
        self.call += o.call;
    }
}

/// Where an output goes: an lvalue expression such as `phi[3]` or `d[2][5]`.
#[derive(Clone)]
pub struct Output {
    pub target: TokenStream,
    pub node: Id,
}

/// Emits straight-line code for a set of outputs of one graph.
pub struct Emitter<'a> {
    pub graph: &'a Graph,
    pub scalar: Scalar,
    pub params: Vec<Ident>,
    /// Names of the coordinates, for readable bindings of sin/cos of body angles.
    pub coordinate_names: Vec<String>,
    /// Methods holding the parts of functions too large to compile as one (see
    /// [`Emitter::body_in_parts`]), for the mechanism's inherent `impl`.
    pub parts: RefCell<Vec<TokenStream>>,
    /// How many nodes of the whole graph have each node as a child ([`Emitter::fused_product`]).
    pub parents: Vec<u32>,
}

/// The signature shared by a function's parts: the parameters each part takes (besides
/// `&self`) and the arguments the function passes them, e.g. `q: &[f64; 9], jv: &mut [f64; 23]`
/// and `q, &mut jv`.
pub struct PartSignature {
    pub name: &'static str,
    pub params: TokenStream,
    pub args: TokenStream,
}

/// Expression nodes up to which a function is emitted whole. Beyond, its outputs are split into
/// parts of about this many nodes, each its own method: rustc's type and borrow checking and
/// LLVM's instruction selection and scheduling grow faster than linearly in a function's
/// length (measured on straight-line code with `rustc -O`: 80 000 statements took 6.4× as long
/// as 20 000, and eight functions of 10 000 took 12.9 s where one of 80 000 took 19.4 s), so a
/// 240-body chain built 2.36× slower than a 120-body one. A part recomputes what it shares with another (the sines and cosines of the bodies at
/// its ends); the outputs are ordered by the first coordinate they read, so a part covers
/// neighbouring bodies and shares little — in a chain. Where the parts would repeat more than
/// [`PART_OVERHEAD`] of the work — a body every other one hangs from, as a vehicle's chassis: cut
/// into parts, the 13-body vehicle of the scene benchmark repeated 79 % of its `accelerations`'
/// 13 043 nodes and 300 % of its Newton matrix's 63 922 — the function is emitted whole. (A
/// 120-link chain's parts repeat 0.4 %; the vehicle's position projection, 11 %.)
pub const PART_NODES: usize = 2000;

/// The most the parts of a function may repeat, as a fraction of its nodes emitted whole, for
/// it to be cut into them.
pub const PART_OVERHEAD: f64 = 0.2;

struct Plan {
    /// Nodes bound with `let`, with their binding names.
    bound: BTreeMap<Id, Ident>,
    /// sin/cos pairs of one argument: argument → (sin node, cos node).
    pairs: HashMap<Id, (Id, Id)>,
}

impl Emitter<'_> {
    fn real(&self) -> TokenStream {
        match self.scalar {
            Scalar::F32 => quote!(f32),
            Scalar::F64 => quote!(f64),
        }
    }

    /// A literal of the scalar type. Non-finite constants are rejected before emission.
    pub fn literal(&self, v: f64) -> TokenStream {
        // `Literal::f32_suffixed` and `f64_suffixed` panic on a non-finite value; `check_finite`
        // reports those as errors first, and this keeps the macro from panicking regardless.
        let scalar = match self.scalar {
            Scalar::F32 => quote!(f32),
            Scalar::F64 => quote!(f64),
        };
        let representable = match self.scalar {
            Scalar::F32 => (v as f32).is_finite(),
            Scalar::F64 => v.is_finite(),
        };
        if !representable {
            let constant = if v.is_nan() {
                quote!(NAN)
            } else if v > 0.0 {
                quote!(INFINITY)
            } else {
                quote!(NEG_INFINITY)
            };
            return quote!(::core::primitive::#scalar::#constant);
        }
        let lit = match self.scalar {
            Scalar::F32 => Literal::f32_suffixed(v.abs() as f32),
            Scalar::F64 => Literal::f64_suffixed(v.abs()),
        };
        if v.is_sign_negative() && v != 0.0 {
            quote!((-#lit))
        } else {
            quote!(#lit)
        }
    }

    /// The product a sum is written as a fused multiply-add with (`Real::fused_mul_add`):
    /// (product, x, y, addend) for `x·y + addend`, the sum's first operand that is a product no
    /// other node of the graph reads, unless either operand is a negation (that sum is written
    /// `a - b`). Decided by the whole graph, not by the function being written, so that every
    /// function writing the sum rounds it alike (a fused evaluation and its parts agree bitwise
    /// with FMA too); a product read elsewhere as well is computed once, as before.
    fn fused_product(&self, id: Id) -> Option<(Id, Id, Id, Id)> {
        let g = self.graph;
        let Node::Add(a, b) = g.node(id) else { return None };
        let alone = |p: Id| self.parents.get(p as usize) == Some(&1);
        match (g.node(a), g.node(b)) {
            (Node::Neg(_), _) | (_, Node::Neg(_)) => None,
            (Node::Mul(x, y), _) if alone(a) => Some((a, x, y, b)),
            (_, Node::Mul(x, y)) if alone(b) => Some((b, x, y, a)),
            _ => None,
        }
    }

    /// The nodes the code of `id` reads: its children, except that `a + (−b)` reads b (it is
    /// written `a - b`, the negation never materialized), a fused sum reads its product's
    /// factors, and x² and x³ read their base twice (they are written as products).
    fn reads(&self, id: Id) -> Vec<Id> {
        let g = self.graph;
        if let Some((_, x, y, c)) = self.fused_product(id) {
            return vec![x, y, c];
        }
        match g.node(id) {
            Node::Add(a, b) => [a, b].iter().map(|&c| if let Node::Neg(x) = g.node(c) { x } else { c }).collect(),
            Node::PowI(a, n) if (2..=3).contains(&n.abs()) => vec![a; 2],
            _ => g.children(id).into_iter().flatten().collect(),
        }
    }

    /// Counts how often each node is read by the code that will be emitted.
    fn plan(&self, outputs: &[Output]) -> Plan {
        let g = self.graph;
        let mut uses: HashMap<Id, u32> = HashMap::new();
        let mut visited = HashSet::new();
        let mut stack: Vec<Id> = outputs.iter().map(|o| o.node).collect();
        for o in outputs {
            *uses.entry(o.node).or_default() += 1;
        }
        let mut sines: HashMap<Id, Id> = HashMap::new();
        let mut cosines: HashMap<Id, Id> = HashMap::new();
        while let Some(id) = stack.pop() {
            if !visited.insert(id) {
                continue;
            }
            match g.node(id) {
                Node::Call(Func::Sin, a) => {
                    sines.insert(a, id);
                }
                Node::Call(Func::Cos, a) => {
                    cosines.insert(a, id);
                }
                _ => {}
            }
            let reads = self.reads(id);
            for c in reads {
                *uses.entry(c).or_default() += 1;
                stack.push(c);
            }
        }
        let pairs: HashMap<Id, (Id, Id)> = sines.iter().filter_map(|(a, &s)| cosines.get(a).map(|&c| (*a, (s, c)))).collect();
        let mut bound = BTreeMap::new();
        for (&id, &n) in &uses {
            let leaf = matches!(g.node(id), Node::Const(_) | Node::Var(_));
            if leaf || !visited.contains(&id) {
                continue;
            }
            if n >= 2 {
                bound.insert(id, format_ident!("v{}", id));
            }
        }
        for (&arg, &(s, c)) in &pairs {
            let (sn, cn) = self.trig_names(arg, s, c);
            bound.insert(s, sn);
            bound.insert(c, cn);
        }
        Plan { bound, pairs }
    }

    /// The nodes the outputs read, themselves included, in ascending id: a topological order,
    /// children before parents.
    fn reached(&self, outputs: &[Output]) -> Vec<Id> {
        let mut reached: Vec<Id> = Vec::new();
        let mut seen = HashSet::new();
        let mut stack: Vec<Id> = outputs.iter().map(|o| o.node).collect();
        while let Some(id) = stack.pop() {
            if seen.insert(id) {
                reached.push(id);
                stack.extend(self.graph.children(id).into_iter().flatten());
            }
        }
        reached.sort_unstable();
        reached
    }

    /// The expression nodes (operations and calls, not constants or variables) that computing
    /// the outputs takes: the measure of a function's size behind [`PART_NODES`].
    pub fn nodes(&self, outputs: &[Output]) -> usize {
        self.reached(outputs).into_iter().filter(|&id| !matches!(self.graph.node(id), Node::Const(_) | Node::Var(_))).count()
    }

    /// What [`Emitter::body`] would count for the outputs, without writing the code: every
    /// operation the outputs reach is written once (bound if read twice, in place if once), and
    /// a sine and cosine of one argument are one `sin_cos` call.
    pub fn count(&self, outputs: &[Output]) -> Ops {
        let g = self.graph;
        let mut ops = Ops::default();
        let (mut sines, mut cosines) = (HashSet::new(), HashSet::new());
        let mut seen = HashSet::new();
        let mut stack: Vec<Id> = outputs.iter().map(|o| o.node).collect();
        while let Some(id) = stack.pop() {
            if !seen.insert(id) {
                continue;
            }
            let node = g.node(id);
            ops += Ops::of(node);
            // A fused sum does its product's multiplication itself.
            if let Some((product, ..)) = self.fused_product(id) {
                ops += Ops::of(g.node(product));
            }
            match node {
                Node::Call(Func::Sin, a) => sines.insert(a),
                Node::Call(Func::Cos, a) => cosines.insert(a),
                _ => false,
            };
            stack.extend(self.reads(id));
        }
        ops.call -= sines.intersection(&cosines).count() as u32;
        ops
    }

    /// Readable names for sin/cos of a body angle (`s_crank`, `c_crank`).
    fn trig_names(&self, arg: Id, s: Id, c: Id) -> (Ident, Ident) {
        if let Node::Var(Var::Q(i)) = self.graph.node(arg) {
            if let Some(name) = self.coordinate_names.get(i as usize) {
                if let Some(body) = name.strip_suffix(".phi") {
                    return (format_ident!("s_{}", body), format_ident!("c_{}", body));
                }
            }
        }
        (format_ident!("s{}", s), format_ident!("c{}", c))
    }

    fn var(&self, v: Var) -> TokenStream {
        match v {
            Var::Q(i) => {
                let i = Literal::usize_unsuffixed(i as usize);
                quote!(q[#i])
            }
            // The velocity v (planar: v = q̇), named `v` in every generated signature.
            Var::Qd(i) => {
                let i = Literal::usize_unsuffixed(i as usize);
                quote!(v[#i])
            }
            Var::T => quote!(t),
            Var::Lambda(i) => {
                let i = Literal::usize_unsuffixed(i as usize);
                quote!(lambda[#i])
            }
            Var::Dir(i) => {
                let i = Literal::usize_unsuffixed(i as usize);
                quote!(dir[#i])
            }
            Var::Param(k) => {
                let p = &self.params[k as usize];
                quote!(self.#p)
            }
        }
    }

    /// The expression computing `id`: its binding if bound, else written in place.
    fn expr(&self, id: Id, plan: &Plan, ops: &mut Ops) -> TokenStream {
        if let Some(name) = plan.bound.get(&id) {
            return quote!(#name);
        }
        self.definition(id, plan, ops)
    }

    /// x·y + c, a sum of the product node `product` = Mul(x, y) ([`Self::fused_product`]): one
    /// fused multiply-add where the target has it (`Real::fused_mul_add`; the same a·b + c
    /// elsewhere), counted as the product's multiplication and the sum's addition.
    fn fused(&self, product: Id, x: Id, y: Id, c: Id, plan: &Plan, ops: &mut Ops) -> TokenStream {
        *ops += Ops::of(self.graph.node(product));
        let real = self.real();
        let (x, y, c) = (self.expr(x, plan, ops), self.expr(y, plan, ops), self.expr(c, plan, ops));
        quote!(<#real as ::mbd::Real>::fused_mul_add(#x, #y, #c))
    }

    /// The right-hand side of a node, reading its children.
    fn definition(&self, id: Id, plan: &Plan, ops: &mut Ops) -> TokenStream {
        let g = self.graph;
        let real = self.real();
        let call = |name: &str| {
            let f = format_ident!("{}", name);
            quote!(<#real as ::mbd::Real>::#f)
        };
        *ops += Ops::of(g.node(id));
        if let Some((product, x, y, c)) = self.fused_product(id) {
            return self.fused(product, x, y, c, plan, ops);
        }
        match g.node(id) {
            Node::Const(bits) => self.literal(f64::from_bits(bits)),
            Node::Var(v) => self.var(v),
            Node::Add(a, b) => match (g.node(a), g.node(b)) {
                (Node::Neg(x), _) => {
                    let (b, x) = (self.expr(b, plan, ops), self.expr(x, plan, ops));
                    quote!((#b - #x))
                }
                (_, Node::Neg(y)) => {
                    let (a, y) = (self.expr(a, plan, ops), self.expr(y, plan, ops));
                    quote!((#a - #y))
                }
                _ => {
                    let (a, b) = (self.expr(a, plan, ops), self.expr(b, plan, ops));
                    quote!((#a + #b))
                }
            },
            Node::Mul(a, b) => {
                let (a, b) = (self.expr(a, plan, ops), self.expr(b, plan, ops));
                quote!((#a * #b))
            }
            Node::Div(a, b) => {
                let (a, b) = (self.expr(a, plan, ops), self.expr(b, plan, ops));
                quote!((#a / #b))
            }
            Node::Neg(a) => {
                let a = self.expr(a, plan, ops);
                quote!((-#a))
            }
            Node::PowI(a, n) => {
                let base = self.expr(a, plan, ops);
                let one = self.literal(1.0);
                match n {
                    2 => {
                        quote!((#base * #base))
                    }
                    3 => {
                        quote!((#base * #base * #base))
                    }
                    -1 => {
                        quote!((#one / #base))
                    }
                    -2 => {
                        quote!((#one / (#base * #base)))
                    }
                    -3 => {
                        quote!((#one / (#base * #base * #base)))
                    }
                    n => {
                        let f = call("powi");
                        let n = Literal::i32_unsuffixed(n);
                        quote!(#f(#base, #n))
                    }
                }
            }
            Node::Pow(a, b) => {
                let f = call("powf");
                let (a, b) = (self.expr(a, plan, ops), self.expr(b, plan, ops));
                quote!(#f(#a, #b))
            }
            Node::Call(func, a) => {
                let f = call(func.name());
                let a = self.expr(a, plan, ops);
                quote!(#f(#a))
            }
            Node::Atan2(y, x) => {
                let f = call("atan2");
                let (y, x) = (self.expr(y, plan, ops), self.expr(x, plan, ops));
                quote!(#f(#y, #x))
            }
            // A branch read only here is computed inside it; a shared one is a temporary. A
            // comparison counts as an addition.
            Node::Select(cmp, a, b, x, y) => {
                let (a, b) = (self.expr(a, plan, ops), self.expr(b, plan, ops));
                let (x, y) = (self.expr(x, plan, ops), self.expr(y, plan, ops));
                match cmp {
                    Cmp::Gt => quote!((if #a > #b { #x } else { #y })),
                    Cmp::Ge => quote!((if #a >= #b { #x } else { #y })),
                }
            }
        }
    }

    /// The statement binding a temporary: its definition, or the `sin_cos` of a sine and cosine
    /// of one argument (once for the pair; `None` for the second of the two).
    fn binding(&self, id: Id, name: &Ident, plan: &Plan, ops: &mut Ops, done_pairs: &mut HashSet<Id>) -> Option<TokenStream> {
        let real = self.real();
        let pair = match self.graph.node(id) {
            Node::Call(Func::Sin | Func::Cos, a) => plan.pairs.get(&a).map(|p| (a, *p)),
            _ => None,
        };
        match pair {
            Some((arg, (s, c))) => done_pairs.insert(arg).then(|| {
                ops.call += 1;
                let a = self.expr(arg, plan, ops);
                let (sn, cn) = (&plan.bound[&s], &plan.bound[&c]);
                quote!((#sn, #cn) = <#real as ::mbd::Real>::sin_cos(#a);)
            }),
            None => {
                let def = self.definition(id, plan, ops);
                Some(quote!(#name = #def;))
            }
        }
    }

    /// The declarations of temporaries, [`DECLARED_TOGETHER`] to a `let`.
    fn declarations(&self, names: &[&Ident]) -> Vec<TokenStream> {
        let real = self.real();
        names
            .chunks(DECLARED_TOGETHER)
            .map(|chunk| match chunk {
                [one] => quote!(let #one: #real;),
                _ => {
                    let types = chunk.iter().map(|_| &real);
                    quote!(let (#(#chunk),*): (#(#types),*);)
                }
            })
            .collect()
    }

    /// Code for outputs computed in stages that share their temporaries, for a loop that runs
    /// the stages in turn and may leave after any of them (a Newton iteration: Φ, the convergence
    /// test, then D): a prologue, computed once before the loop, with every maximal subexpression
    /// that depends on neither coordinates, velocities nor multipliers (`sin(t + 1)` of a driver;
    /// with the declarations of all the temporaries); then each stage's statements, each
    /// temporary in the first stage that reads it. A temporary of a later stage is assigned
    /// after the earlier stages' statements, so the loop may leave before it is computed.
    pub fn staged(&self, stages: &[&[Output]]) -> (TokenStream, Vec<TokenStream>) {
        let state = |v: &Var| matches!(v, Var::Q(_) | Var::Qd(_) | Var::Lambda(_) | Var::Dir(_));
        let (prologue, stages, _) = self.staged_over(stages, state);
        (prologue, stages)
    }

    /// [`staged`](Self::staged) with the state the stages depend on chosen by `state`: the
    /// prologue holds every maximal subexpression of the other variables. Over `Var::Dir` alone,
    /// for a loop over right-hand sides (`Dynamics::solve_mass_rows`): what depends on q only —
    /// a tree's articulated inertias and their factors — is computed once before it. Also
    /// returns the operations of the prologue, then of each stage.
    pub fn staged_over(&self, stages: &[&[Output]], state: impl Fn(&Var) -> bool) -> (TokenStream, Vec<TokenStream>, Vec<Ops>) {
        let g = self.graph;
        let all: Vec<Output> = stages.iter().flat_map(|s| s.iter().cloned()).collect();
        let mut plan = self.plan(&all);
        // Which nodes depend on the state, in ascending id (children first).
        let reached = self.reached(&all);
        let mut reads: HashSet<Id> = HashSet::new();
        for &id in &reached {
            let reads_state = match g.node(id) {
                Node::Var(v) => state(&v),
                _ => g.children(id).into_iter().flatten().any(|c| reads.contains(&c)),
            };
            if reads_state {
                reads.insert(id);
            }
        }
        // A negation is written into its reader (`a - b`): what it negates is what is read.
        let read = |id: Id| if let Node::Neg(x) = g.node(id) { x } else { id };
        let costly = |id: Id| !matches!(g.node(id), Node::Const(_) | Node::Var(_) | Node::Neg(_));
        // Maximal time-only subexpressions: read by a node of the state or by an output.
        let mut hoisted: HashSet<Id> = HashSet::new();
        for &id in &reached {
            if reads.contains(&id) {
                for c in self.reads(id).into_iter().map(read) {
                    if !reads.contains(&c) && costly(c) {
                        hoisted.insert(c);
                    }
                }
            }
        }
        for o in &all {
            let c = read(o.node);
            if !reads.contains(&c) && costly(c) {
                hoisted.insert(c);
            }
        }
        for &id in &hoisted {
            plan.bound.entry(id).or_insert_with(|| format_ident!("v{}", id));
        }
        // Bound time-only nodes inside a hoisted one are computed with it.
        for &id in &reached {
            if plan.bound.contains_key(&id) && !reads.contains(&id) {
                hoisted.insert(id);
            }
        }
        // The first stage reading each bound node of the state.
        let mut stage_of: HashMap<Id, usize> = HashMap::new();
        for (k, stage) in stages.iter().enumerate() {
            let mut stack: Vec<Id> = stage.iter().map(|o| o.node).collect();
            while let Some(id) = stack.pop() {
                if stage_of.contains_key(&id) || hoisted.contains(&id) {
                    continue;
                }
                stage_of.insert(id, k);
                stack.extend(g.children(id).into_iter().flatten());
            }
        }
        // sin and cos of one argument are one `sin_cos`, in the earlier of their stages.
        for (s, c) in plan.pairs.values().copied().collect::<Vec<_>>() {
            if let (Some(&a), Some(&b)) = (stage_of.get(&s), stage_of.get(&c)) {
                stage_of.insert(s, a.min(b));
                stage_of.insert(c, a.min(b));
            }
        }
        // ops[0]: the prologue's; ops[k + 1]: stage k's.
        let mut ops = vec![Ops::default(); stages.len() + 1];
        let mut done_pairs = HashSet::new();
        let mut prologue = Vec::new();
        let mut statements: Vec<Vec<TokenStream>> = vec![Vec::new(); stages.len()];
        for (&id, name) in &plan.bound {
            let (into, count) = match stage_of.get(&id) {
                _ if hoisted.contains(&id) => (&mut prologue, &mut ops[0]),
                Some(&k) => (&mut statements[k], &mut ops[k + 1]),
                None => continue,
            };
            into.extend(self.binding(id, name, &plan, count, &mut done_pairs));
        }
        for (k, stage) in stages.iter().enumerate() {
            for o in stage.iter() {
                let target = &o.target;
                let value = self.expr(o.node, &plan, &mut ops[k + 1]);
                statements[k].push(quote!(#target = #value;));
            }
        }
        let declare = |names: Vec<&Ident>| self.declarations(&names);
        let hoisted_names = declare(plan.bound.iter().filter(|(id, _)| hoisted.contains(id)).map(|(_, n)| n).collect());
        let stage_names =
            declare(plan.bound.iter().filter(|(id, _)| stage_of.contains_key(id) && !hoisted.contains(id)).map(|(_, n)| n).collect());
        let prologue = quote!(#(#hoisted_names)* #(#prologue)*);
        let mut out: Vec<TokenStream> = statements.iter().map(|s| scalarized_blocks(s, BLOCK_STATEMENTS)).collect();
        if let Some(first) = out.first_mut() {
            *first = quote!(#(#stage_names)* #first);
        }
        (prologue, out, ops)
    }

    /// Straight-line statements computing every output, and their operation count.
    ///
    /// The temporaries are declared first, [`DECLARED_TOGETHER`] to a `let`, and assigned after:
    /// a `let` per temporary opens a debug-info scope inside the previous one, and LLVM recursed
    /// through 27 000 of them until rustc's stack overflowed (a debug build of a 13-body spatial
    /// vehicle, whose `forces_q` has that many).
    pub fn body(&self, outputs: &[Output]) -> (TokenStream, Ops) {
        let plan = self.plan(outputs);
        let mut ops = Ops::default();
        let mut stmts = Vec::new();
        let mut done_pairs = HashSet::new();
        // Ascending id is a topological order: children are created before their parents.
        for (&id, name) in &plan.bound {
            stmts.extend(self.binding(id, name, &plan, &mut ops, &mut done_pairs));
        }
        for o in outputs {
            let target = &o.target;
            let value = self.expr(o.node, &plan, &mut ops);
            stmts.push(quote!(#target = #value;));
        }
        let names: Vec<&Ident> = plan.bound.values().collect();
        let declarations = self.declarations(&names);
        let stmts = in_blocks(&stmts);
        (quote!(#(#declarations)* #stmts), ops)
    }

    /// As [`Emitter::body`], for a function that may be too large to compile as one: above
    /// [`PART_NODES`] expression nodes the outputs, ordered by the first coordinate each reads,
    /// are cut into parts of about that many nodes — unless they would repeat more than
    /// [`PART_OVERHEAD`] of the work; each part becomes a method
    /// `__mbd_{name}_{k}(&self, params)` (collected in [`Emitter::parts`]) and the returned code
    /// calls them in turn. The operation count is the parts' sum.
    pub fn body_in_parts(&self, outputs: &[Output], signature: &PartSignature) -> (TokenStream, Ops) {
        let g = self.graph;
        let reached = self.reached(outputs);
        let costly = |id: Id| !matches!(g.node(id), Node::Const(_) | Node::Var(_));
        if self.nodes(outputs) <= PART_NODES {
            return self.body(outputs);
        }
        // The first coordinate or velocity each node reads.
        let mut first: HashMap<Id, u32> = HashMap::new();
        for &id in &reached {
            let own = match g.node(id) {
                Node::Var(Var::Q(i) | Var::Qd(i)) => u32::from(i),
                _ => u32::MAX,
            };
            let key = g.children(id).into_iter().flatten().map(|c| first[&c]).fold(own, u32::min);
            first.insert(id, key);
        }
        let mut ordered: Vec<&Output> = outputs.iter().collect();
        ordered.sort_by_key(|o| first[&o.node]);
        // Greedy cut: a part closes when the next output would take it past PART_NODES.
        let whole = reached.iter().filter(|&&id| costly(id)).count();
        let mut groups: Vec<Vec<Output>> = vec![Vec::new()];
        let (mut in_part, mut size, mut closed): (HashSet<Id>, usize, usize) = (HashSet::new(), 0, 0);
        for o in ordered {
            let mut new = HashSet::new();
            let mut stack = vec![o.node];
            while let Some(id) = stack.pop() {
                if !in_part.contains(&id) && new.insert(id) {
                    stack.extend(g.children(id).into_iter().flatten());
                }
            }
            let added = new.iter().filter(|&&id| costly(id)).count();
            if !groups.last().expect("a part").is_empty() && size + added > PART_NODES {
                // A new part reads everything the output reads.
                groups.push(Vec::new());
                in_part.clear();
                closed += size;
                size = 0;
                let mut stack = vec![o.node];
                while let Some(id) = stack.pop() {
                    if in_part.insert(id) {
                        size += usize::from(costly(id));
                        stack.extend(g.children(id).into_iter().flatten());
                    }
                }
            } else {
                in_part.extend(new);
                size += added;
            }
            groups.last_mut().expect("a part").push(o.clone());
        }
        if (closed + size) as f64 > (1.0 + PART_OVERHEAD) * whole as f64 {
            return self.body(outputs);
        }
        let mut ops = Ops::default();
        let mut calls = Vec::new();
        let mut parts = self.parts.borrow_mut();
        let PartSignature { name, params, args } = signature;
        for group in groups {
            let (code, part_ops) = self.body(&group);
            ops += part_ops;
            let method = format_ident!("__mbd_{}_{}", name, parts.len());
            parts.push(quote! {
                #[inline(never)]
                fn #method(&self, #params) {
                    #code
                }
            });
            calls.push(quote!(self.#method(#args);));
        }
        (quote!(#(#calls)*), ops)
    }
}

/// Statements per basic block in long straight-line sequences (see [`in_blocks`]).
pub const BLOCK_STATEMENTS: usize = 256;

/// Straight-line statements, cut every [`BLOCK_STATEMENTS`] into basic blocks that LLVM cannot
/// merge (a branch on an opaque `false` around an empty `black_box`; a few cycles each). LLVM's
/// SLP vectorizer, instruction selection and scheduler work one basic block at a time and grow
/// faster than linearly in its length: in a 240-body chain's build the vectorizer alone took
/// 8.5 s, 3.4 times as long on its `accelerations` as at 120 bodies. Shorter sequences (every mechanism of a few dozen
/// bodies) are emitted as they are.
///
/// Array accesses by literal index are read and written through bindings of the elements, made
/// block by block ([`crate::scalar`]: rustc type-checks an index expression in about 100 µs,
/// and a binding's borrow spans at most its block).
pub fn in_blocks(stmts: &[TokenStream]) -> TokenStream {
    if stmts.len() <= 2 * BLOCK_STATEMENTS {
        return scalarize(quote!(#(#stmts)*));
    }
    let blocks = stmts.chunks(BLOCK_STATEMENTS).map(|block| scalarize(quote!(#(#block)*)));
    quote!(#(#blocks if ::core::hint::black_box(false) { ::core::hint::black_box(()); })*)
}

/// Statements of one function up to which [`in_functions`] keeps them in it.
pub const STATEMENTS_PER_FUNCTION: usize = 256;

/// Straight-line array code (`b[3] -= l[5] * b[1];`) as [`in_blocks`] does, or, above
/// [`STATEMENTS_PER_FUNCTION`] statements, as nested `#[inline(never)]` functions of about that
/// many statements, called in turn. LLVM's instruction selection and register allocation work
/// on a whole function and grow faster than linearly in its length (the 240-body chain's
/// `accelerations`, whose linear algebra is such code, took 3.2 times as long to compile as the
/// 120-body chain's, `-Zllvm-time-trace`); functions of bounded length make it linear.
///
/// The functions are named `__mbd_{label}_{k}`: one label per sequence of a function body.
/// Each nested function takes the arrays its statements index, by reference (mutable if it
/// writes them; generic over their lengths, through `mbd::__private::Elements::all`, which serves
/// local arrays and references alike), and the `scalars` they read, of the scalar type `real`.
/// Code that reads anything else (a temporary, `self`), declares a local or may return early
/// stays in one function: a nested function could not see it, or would change what `return`
/// leaves.
pub fn in_functions(stmts: &[TokenStream], label: &str, scalars: &[&str], real: &TokenStream) -> TokenStream {
    if stmts.len() <= STATEMENTS_PER_FUNCTION {
        return in_blocks(stmts);
    }
    let Some(groups) =
        stmts.chunks(STATEMENTS_PER_FUNCTION).map(|group| crate::scalar::free_arrays(group, scalars)).collect::<Option<Vec<_>>>()
    else {
        return in_blocks(stmts);
    };
    let functions = stmts.chunks(STATEMENTS_PER_FUNCTION).zip(groups).enumerate().map(|(k, (group, arrays))| {
        let name = format_ident!("__mbd_{}_{}", label, k);
        let mut generics = Vec::new();
        let mut params = Vec::new();
        let mut args = Vec::new();
        for (array, written) in &arrays.arrays {
            let (ident, length) = (format_ident!("{}", array), format_ident!("N_{}", array.to_uppercase()));
            generics.push(quote!(const #length: usize));
            if *written {
                params.push(quote!(#ident: &mut [#real; #length]));
                args.push(quote!(#ident.all_mut()));
            } else {
                params.push(quote!(#ident: &[#real; #length]));
                args.push(quote!(#ident.all()));
            }
        }
        for scalar in &arrays.scalars {
            let ident = format_ident!("{}", scalar);
            params.push(quote!(#ident: #real));
            args.push(quote!(#ident));
        }
        let body = in_blocks(group);
        quote! {
            #[inline(never)]
            #[allow(clippy::too_many_arguments, non_snake_case)]
            fn #name<#(#generics),*>(#(#params),*) {
                #body
            }
            {
                use ::mbd::__private::Elements as _;
                #name(#(#args),*);
            }
        }
    });
    quote!(#(#functions)*)
}

/// Statements with their array accesses made element bindings ([`crate::scalar`]) in groups of
/// `per_group`, so that no binding's borrow spans more than a group; not cut into basic blocks.
pub fn scalarized_blocks(stmts: &[TokenStream], per_group: usize) -> TokenStream {
    let groups = stmts.chunks(per_group.max(1)).map(|group| scalarize(quote!(#(#group)*)));
    quote!(#(#groups)*)
}

/// Constraint rows up to which the generated functions are `#[inline]` and the LDLᵀ of the Schur
/// complement is inlined into its callers.
pub const INLINE_ROWS: usize = 64;

/// `#[inline]` on a generated function of a mechanism of up to [`INLINE_ROWS`] constraint rows,
/// where a call's cost matters; nothing above, so that each function is compiled once, not once
/// in every codegen unit that calls it (a 240-body chain's `accelerations` was compiled five
/// times, 12 s of its build).
pub fn inline_hint(rows: usize) -> TokenStream {
    if rows <= INLINE_ROWS {
        quote!(#[inline])
    } else {
        quote!()
    }
}

/// Temporaries declared by one `let` in [`Emitter::body`].
const DECLARED_TOGETHER: usize = 64;

/// Rejects constants that are not finite in the scalar type (e.g. `ln(0)` folded at compile
/// time, or 1e39 in f32): they would make every evaluation NaN or infinite. A parameter's
/// default is reported on the parameter.
pub fn check_finite(model: &Model, f: &Formulation, span: Span) -> syn::Result<()> {
    let fits = |v: f64| match model.scalar {
        Scalar::F32 => (v as f32).is_finite(),
        Scalar::F64 => v.is_finite(),
    };
    for p in &model.params {
        if !fits(p.default) {
            return Err(syn::Error::new(
                p.name.span(),
                format!("the default of `{}` is beyond the range of f32: expected at most ±3.4e38, found {:e}", p.name, p.default),
            ));
        }
    }
    let jac = f.jacobian.iter().map(|e| &e.2);
    let h_q = f.h_q.iter().chain(&f.h_qd).chain(&f.constraint_force_q).map(|e| &e.2);
    let roots = f.phi.iter().chain(jac).chain(&f.nu).chain(&f.gamma).chain(&f.q0).chain(&f.qd0);
    let roots = roots.chain(&f.mass).chain(&f.h).chain(&f.friction).chain(h_q).chain(std::iter::once(&f.potential));
    for &r in roots {
        let mut stack = vec![r];
        let mut seen = HashSet::new();
        while let Some(id) = stack.pop() {
            if !seen.insert(id) {
                continue;
            }
            if let Some(v) = f.graph.as_const(id) {
                if !v.is_finite() {
                    return Err(syn::Error::new(
                        span,
                        format!("an expression of this mechanism is not finite: expected a finite value, found {v} for every state (a constant such as ln(0) or 1/0)"),
                    ));
                }
                if !fits(v) {
                    return Err(syn::Error::new(
                        span,
                        format!("an expression of this mechanism is beyond the range of f32: expected at most ±3.4e38, found {v:e}"),
                    ));
                }
            }
            stack.extend(f.graph.children(id).into_iter().flatten());
        }
    }
    Ok(())
}

/// The emitter of a model's formulation.
pub fn emitter<'a>(model: &Model, f: &'a Formulation) -> Emitter<'a> {
    Emitter {
        graph: &f.graph,
        scalar: model.scalar,
        params: model.params.iter().map(|p| p.name.clone()).collect(),
        coordinate_names: model.coordinate_names(),
        parts: RefCell::new(Vec::new()),
        parents: parents(&f.graph),
    }
}

/// How many nodes of `g` have each node as a child.
fn parents(g: &Graph) -> Vec<u32> {
    let mut parents = vec![0; g.node_count()];
    for id in 0..g.node_count() as Id {
        for c in g.children(id).into_iter().flatten() {
            parents[c as usize] += 1;
        }
    }
    parents
}

// --- outputs shared by the generated functions -------------------------------------------

pub fn real(s: Scalar) -> TokenStream {
    match s {
        Scalar::F32 => quote!(f32),
        Scalar::F64 => quote!(f64),
    }
}

pub fn usize_lit(n: usize) -> Literal {
    Literal::usize_unsuffixed(n)
}

/// Outputs `out[i] = nodes[i]`.
pub fn vector_outputs(out: &str, nodes: &[u32]) -> Vec<Output> {
    let out = format_ident!("{}", out);
    nodes
        .iter()
        .enumerate()
        .map(|(i, &node)| {
            let i = usize_lit(i);
            Output { target: quote!(#out[#i]), node }
        })
        .collect()
}

/// Outputs `hf[i] = friction force on coordinate i` for the coordinates friction acts on.
pub fn friction_outputs(f: &Formulation) -> Vec<Output> {
    f.friction
        .iter()
        .enumerate()
        .filter(|(_, &node)| !f.graph.is_zero(node))
        .map(|(i, &node)| {
            let i = usize_lit(i);
            Output { target: quote!(hf[#i]), node }
        })
        .collect()
}

/// Outputs `name[k] = Φ_q`'s k-th structural non-zero.
pub fn jacobian_values_outputs(f: &Formulation, name: &str) -> Vec<Output> {
    let name = format_ident!("{}", name);
    f.jacobian
        .iter()
        .enumerate()
        .map(|(k, &(_, _, node))| {
            let k = usize_lit(k);
            Output { target: quote!(#name[#k]), node }
        })
        .collect()
}

/// The code that computes the friction forces' slopes in the multipliers (`f.friction_lambda`,
/// in its order) into a local array, and that array's name. A slope that is not finite — a
/// revolute joint's load |(λ_x, λ_y)| at exactly zero, whose derivative is 0/0 there — is
/// taken as 0: it only enters an iteration matrix, where any bounded slope keeps the iteration
/// converging, and a NaN there would stop it.
pub fn multiplier_slopes(f: &Formulation, e: &Emitter) -> (TokenStream, Ident) {
    let name = format_ident!("friction_slopes");
    let outputs: Vec<Output> = f
        .friction_lambda
        .iter()
        .enumerate()
        .map(|(k, &(_, _, node))| {
            let k = usize_lit(k);
            Output { target: quote!(#name[#k]), node }
        })
        .collect();
    let (body, _) = e.body(&outputs);
    let (zero, n) = (e.literal(0.0), usize_lit(f.friction_lambda.len()));
    let fill = quote! {
        let mut #name = [#zero; #n];
        #body
        for x in #name.iter_mut() {
            if !x.is_finite() {
                *x = #zero;
            }
        }
    };
    (fill, name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::MechanismDef;

    /// A node read by two outputs is bound once with `let`; sin and cos of one angle become one
    /// `sin_cos` call; the operation count is what the code does.
    #[test]
    fn shared_nodes_are_bound_once() {
        let model = syn::parse_str::<MechanismDef>("P { body a { mass: 1.0, inertia: 0.1 } revolute ground[0.0, 0.0] ~ a[-1.0, 0.0]; }")
            .unwrap()
            .validate()
            .unwrap();
        let f = crate::formulation::formulate(&model);
        let e = emitter(&model, &f);
        let (code, ops) = e.body(&vector_outputs("phi", &f.phi));
        let code = code.to_string();
        assert_eq!(code.matches("sin_cos").count(), 1, "{code}");
        assert!(!code.contains(":: sin (") && !code.contains(":: cos ("), "{code}");
        assert_eq!(ops.call, 1, "one sin_cos");
        // Outputs written through bindings of the elements (`crate::scalar`).
        assert!(code.contains("(* __phi_0) =") && code.contains("(* __phi_1) ="), "{code}");
    }

    /// A sum is written as a fused multiply-add with a product that no other node of the graph
    /// reads, whichever function writes it and whatever else that function outputs (so that a
    /// fused evaluation and its parts round alike); a product two nodes read is computed once.
    #[test]
    fn sums_fuse_the_products_only_they_read() {
        let model = syn::parse_str::<MechanismDef>("P { body a { mass: 1.0, inertia: 0.1 } revolute ground[0.0, 0.0] ~ a[-1.0, 0.0]; }")
            .unwrap()
            .validate()
            .unwrap();
        let mut f = crate::formulation::formulate(&model);
        let g = &mut f.graph;
        let (x, y, z) = (g.var(Var::Q(0)), g.var(Var::Q(1)), g.var(Var::Q(2)));
        let alone = g.mul(x, y);
        let fused = g.add(alone, z);
        let shared = g.mul(x, z);
        let (sum, product) = (g.add(shared, y), g.mul(shared, y));
        let e = emitter(&model, &f);
        let write = |nodes: &[Id]| {
            let outputs: Vec<Output> = nodes.iter().enumerate().map(|(k, &node)| Output { target: quote!(out[#k]), node }).collect();
            e.body(&outputs).0.to_string()
        };
        for outputs in [&[fused][..], &[fused, alone], &[fused, sum, product]] {
            let code = write(outputs);
            assert_eq!(code.matches("fused_mul_add").count(), 1, "{code}");
        }
        let code = write(&[sum, product]);
        assert!(!code.contains("fused_mul_add"), "{code}");
        // The fused sum counts its product's multiplication, and the count agrees with writing.
        let outputs = [Output { target: quote!(out[0]), node: fused }];
        assert_eq!(e.count(&outputs), e.body(&outputs).1);
        assert_eq!((e.count(&outputs).add, e.count(&outputs).mul), (1, 1));
    }

    /// `count` is what `body` counts writing the code, on functions with every kind of node
    /// (powers, divisions, square roots, selects of a contact and a tyre, sin/cos pairs), in the
    /// plane, in space and in joint coordinates.
    #[test]
    fn counting_agrees_with_writing() {
        let sources = [
            "P { gravity [0.0, -9.81]; body a { mass: 1.0, inertia: 0.1, at: [0.5, 0.1, 0.2] } body b { mass: 2.0, inertia: 0.2 }
               revolute ground[0.0, 0.0] ~ a[-0.5, 0.0]; revolute_translational a[0.5, 0.0] ~ b[0.0, 0.0] along [1.0, 0.0];
               spring ground[0.2, 0.0] ~ b[0.1, 0.0] { k: 10.0, length: 0.3, c: 0.5 };
               contact b[0.0, -0.1] ~ ground[0.0, -1.0] along [0.0, 1.0] { k: 1.0e4, exponent: 1.5, c: 10.0 };
               torque a = 0.1 * t^3 / (1.0 + a.phi^2); }",
            "J { joint_coordinates; gravity [0.0, -9.81]; body a { mass: 1.0, inertia: 0.1, at: [0.5, 0.0, 0.0] }
               body b { mass: 2.0, inertia: 0.2, at: [1.0, 0.0, 0.0] } revolute ground[0.0, 0.0] ~ a[-0.5, 0.0];
               revolute a[0.5, 0.0] ~ b[0.0, 0.0]; revolute_revolute ground[1.0, 1.0] ~ b[0.3, 0.0] { length: 1.2 };
               rotational_spring a ~ b { k: 3.0, angle: 0.1, c: 0.2 }; }",
        ];
        for src in sources.iter().copied().chain(std::iter::once(crate::formulation::tests::SPATIAL)) {
            let model = syn::parse_str::<MechanismDef>(src).unwrap().validate().unwrap();
            let f = crate::formulation::formulate(&model);
            let e = emitter(&model, &f);
            let mut outputs = vector_outputs("h", &f.h);
            outputs.extend(vector_outputs("gamma", &f.gamma));
            outputs.extend(vector_outputs("phi", &f.phi));
            for (name, entries) in [("dh", &f.h_q), ("dv", &f.h_qd), ("g", &f.gamma_q)] {
                let name = format_ident!("{}", name);
                outputs.extend(entries.iter().map(|&(r, c, node)| Output { target: quote!(#name[#r][#c]), node }));
            }
            if let Some(terms) = &f.tree {
                outputs.extend(vector_outputs("dq", &terms.h_dq));
                outputs.extend(vector_outputs("mx", &terms.mass_x_dq));
            }
            let ops = e.count(&outputs);
            assert!(ops.total() > 50 && ops.call > 0 && ops.div > 0, "{src}: {ops:?}");
            assert_eq!(ops, e.body(&outputs).1, "{src}");
        }
    }

    /// A chain's `accelerations` is cut into parts (they repeat 0.4 % of it); outputs that all
    /// read one large node, which every part would repeat, are emitted whole.
    #[test]
    fn a_function_is_cut_into_parts_only_where_they_repeat_little() {
        let chain: TokenStream = "C {
            gravity [0.0, -9.81];
            revolute ground[0.0, 0.0] ~ l[0][-0.05, 0.0];
            for k in 0..120 { body l[k] { mass: 0.1, inertia: 8.3e-5, at: [0.05 + 0.1 * k, 0.0, 0.0] } }
            for k in 1..120 { revolute l[k - 1][0.05, 0.0] ~ l[k][-0.05, 0.0]; }
        }"
        .parse()
        .unwrap();
        let chain = crate::expand::expand(chain).to_string();
        assert!(chain.contains("__mbd_accelerations_0"), "the chain's accelerations in parts");
        // Its linear algebra in nested functions of bounded length (`in_functions`).
        for part in ["fn __mbd_minv_h_1", "fn __mbd_lambda_vd_0", "fn __mbd_v_step_1"] {
            assert!(chain.contains(part), "{part}");
        }
        // Outputs that all read one large shared node: parts would repeat it in each.
        let model = syn::parse_str::<MechanismDef>("P { body a { mass: 1.0, inertia: 0.1 } }").unwrap().validate().unwrap();
        let mut f = crate::formulation::formulate(&model);
        let g = &mut f.graph;
        // Σ sin(c_k q₀), summed pairwise (shallow: the graph's walks recurse).
        let q0 = g.var(Var::Q(0));
        let mut terms: Vec<Id> = (0..PART_NODES)
            .map(|k| {
                let c = g.num(1.0 + k as f64);
                let x = g.mul(c, q0);
                g.call(crate::sym::Func::Sin, x)
            })
            .collect();
        while terms.len() > 1 {
            terms = terms.chunks(2).map(|p| if let [a, b] = p { g.add(*a, *b) } else { p[0] }).collect();
        }
        let shared = terms[0];
        let nodes: Vec<Id> = (0..8)
            .map(|k| {
                let c = g.num(k as f64 + 0.5);
                let x = g.var(Var::Q(k % 3));
                let own = g.mul(c, x);
                g.add(shared, own)
            })
            .collect();
        let signature = PartSignature { name: "shared", params: quote!(q: &[f64; 3]), args: quote!(q) };
        let e = emitter(&model, &f);
        let (code, _) = e.body_in_parts(&vector_outputs("out", &nodes), &signature);
        assert!(e.parts.borrow().is_empty() && !code.to_string().contains("__mbd_shared"), "emitted whole");
    }

    /// The position solve's stages: `sin(2t)` of the driver in the prologue, computed once per
    /// solve; Φ's stage with the body angle's `sin_cos`; the Jacobian's stage with what only it
    /// reads (a product of the crank's half length and its angle's cosine).
    #[test]
    fn staged_code_hoists_time_and_leaves_the_jacobian_for_later() {
        let model = syn::parse_str::<MechanismDef>(
            "P { params { l: 2.0 } body a { mass: 1.0, inertia: 0.1 } revolute ground[0.0, 0.0] ~ a[-l / 2.0, 0.0]; \
             drive a.phi = 0.5 * sin(2.0 * t); }",
        )
        .unwrap()
        .validate()
        .unwrap();
        let f = crate::formulation::formulate(&model);
        let e = emitter(&model, &f);
        let (phi, jv) = (vector_outputs("phi", &f.phi), jacobian_values_outputs(&f, "jv"));
        let (prologue, stages) = e.staged(&[&phi, &jv]);
        let (prologue, first, second) = (prologue.to_string(), stages[0].to_string(), stages[1].to_string());
        // Arrays are read and written through bindings of their elements (`crate::scalar`).
        assert!(prologue.contains(":: sin (") && !prologue.contains("__q_"), "{prologue}");
        assert!(!first.contains(":: sin (") && first.contains("sin_cos ((* __q_2))"), "{first}");
        assert!(first.contains("(* __phi_2) =") && !first.contains("__jv_"), "{first}");
        assert!(second.contains("__jv_") && !second.contains("sin_cos") && !second.contains("__phi_"), "{second}");
        // Every temporary the second stage reads is assigned in the prologue, the first stage or
        // the second stage itself: the stages run in order, each assignment before its reads.
        let all = format!("{prologue} {first} {second}");
        for name in second.split(|c: char| !c.is_alphanumeric() && c != '_').filter(|w| w.starts_with('v') && w[1..].parse::<u32>().is_ok())
        {
            assert!(all.contains(&format!("{name} =")), "{name} is read but never assigned:\n{all}");
        }
    }
}
