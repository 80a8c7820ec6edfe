//! The symbolic engine: a hash-consed expression graph with constant folding, algebraic
//! simplification on construction, exact differentiation (forward mode, one seed at a time)
//! and evaluation.
//!
//! Every node is stored once ([`Graph::intern`]): building `sin(φ)` twice yields the same [`Id`],
//! so common subexpressions are shared by construction and emission computes each node once.
//! A child is always created before its parent, so ascending `Id` order is a topological order.

use std::collections::{HashMap, HashSet};

/// Index of a node in a [`Graph`].
pub type Id = u32;

/// A leaf variable of the graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Var {
    /// Generalized coordinate `q[i]`.
    Q(u16),
    /// Generalized velocity `q̇[i]`.
    Qd(u16),
    /// Time `t`.
    T,
    /// Runtime parameter number `i`.
    Param(u16),
    /// Lagrange multiplier `λ[i]` of constraint row `i`.
    Lambda(u16),
    /// Component `i` of a direction `dir[i]`: the seed of a derivative taken at run time one
    /// column at a time ((∂h/∂q) dir), or the vector a generated product applies an operator
    /// to (J_bᵀ w). Joint coordinates emit their dense derivatives this way: O(N) code for each,
    /// where the entries one by one would be O(N²) and more.
    Dir(u16),
}

/// Elementary functions of one argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Func {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sqrt,
    Exp,
    Ln,
}

impl Func {
    /// The name users write and the `Real` method generated code calls.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Sqrt => "sqrt",
            Func::Exp => "exp",
            Func::Ln => "ln",
        }
    }

    /// Looks a function up by the name users write.
    pub fn from_name(name: &str) -> Option<Func> {
        Some(match name {
            "sin" => Func::Sin,
            "cos" => Func::Cos,
            "tan" => Func::Tan,
            "asin" => Func::Asin,
            "acos" => Func::Acos,
            "atan" => Func::Atan,
            "sqrt" => Func::Sqrt,
            "exp" => Func::Exp,
            "ln" => Func::Ln,
            _ => return None,
        })
    }

    fn apply(self, x: f64) -> f64 {
        match self {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Asin => x.asin(),
            Func::Acos => x.acos(),
            Func::Atan => x.atan(),
            Func::Sqrt => x.sqrt(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
        }
    }
}

/// One node of the expression graph. Commutative operands are stored in ascending `Id` order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant, by its bits (`-0.0` is stored as `0.0`).
    Const(u64),
    Var(Var),
    Add(Id, Id),
    Mul(Id, Id),
    Neg(Id),
    Div(Id, Id),
    /// Integer power `a^n`, n ∉ {0, 1}.
    PowI(Id, i32),
    /// Real power `a^b`.
    Pow(Id, Id),
    Call(Func, Id),
    /// `atan2(y, x)`.
    Atan2(Id, Id),
    /// `if a > b { x } else { y }` (or `>=`): the one non-smooth node. `abs`, `sign`, `min`, `max`,
    /// `clamp` and the DSL's `if` are built from it. Its derivative is the derivative of the branch
    /// its value takes — at a tie, the `else` branch of `>` and the `then` branch of `>=` — so it is
    /// one-sided at the kink and never NaN there.
    Select(Cmp, Id, Id, Id, Id),
}

/// The comparison of a [`Node::Select`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Cmp {
    /// `a > b`
    Gt,
    /// `a >= b`
    Ge,
}

impl Cmp {
    pub fn holds(self, a: f64, b: f64) -> bool {
        match self {
            Cmp::Gt => a > b,
            Cmp::Ge => a >= b,
        }
    }
}

/// A hash-consed expression graph.
#[derive(Default)]
pub struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, Id>,
    /// ∂node/∂v already taken, by v ([`Graph::partial`]): the graph only grows, so a node's
    /// partial never changes, and the rows of a Jacobian, of ∂h/∂q and of each force element's
    /// terms alone share most of theirs.
    partials: HashMap<Var, HashMap<Id, Id>>,
}

impl Graph {
    pub fn new() -> Self {
        Self::default()
    }

    /// How many nodes the graph holds (ids 0 to `node_count() - 1`).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The node behind an id.
    pub fn node(&self, id: Id) -> Node {
        self.nodes[id as usize]
    }

    fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = self.nodes.len() as Id;
        self.nodes.push(node);
        self.index.insert(node, id);
        id
    }

    /// The constant `v`.
    pub fn num(&mut self, v: f64) -> Id {
        let v = if v == 0.0 { 0.0 } else { v };
        self.intern(Node::Const(v.to_bits()))
    }

    /// The value of a constant node, if it is one.
    pub fn as_const(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    /// Whether the node is the constant 0 (a structural zero).
    pub fn is_zero(&self, id: Id) -> bool {
        self.as_const(id) == Some(0.0)
    }

    pub fn var(&mut self, v: Var) -> Id {
        self.intern(Node::Var(v))
    }

    pub fn add(&mut self, a: Id, b: Id) -> Id {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => return self.num(x + y),
            (Some(0.0), None) => return b,
            (None, Some(0.0)) => return a,
            _ => {}
        }
        // a + (−a) = 0
        if self.node(b) == Node::Neg(a) || self.node(a) == Node::Neg(b) {
            return self.num(0.0);
        }
        // (−a) + (−b) = −(a + b)
        if let (Node::Neg(x), Node::Neg(y)) = (self.node(a), self.node(b)) {
            let s = self.add(x, y);
            return self.neg(s);
        }
        // c1 + (c2 + x) = (c1 + c2) + x
        if let Some(c1) = self.as_const(a).or(self.as_const(b)) {
            let other = if self.as_const(a).is_some() { b } else { a };
            if let Node::Add(p, r) = self.node(other) {
                let (c2, rest) = match (self.as_const(p), self.as_const(r)) {
                    (Some(c2), _) => (Some(c2), r),
                    (_, Some(c2)) => (Some(c2), p),
                    _ => (None, r),
                };
                if let Some(c2) = c2 {
                    let c = self.num(c1 + c2);
                    return self.add(c, rest);
                }
            }
        }
        // x + x = 2·x
        if a == b {
            let two = self.num(2.0);
            return self.mul(two, a);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Add(a, b))
    }

    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        let nb = self.neg(b);
        self.add(a, nb)
    }

    pub fn neg(&mut self, a: Id) -> Id {
        match self.node(a) {
            Node::Const(bits) => self.num(-f64::from_bits(bits)),
            Node::Neg(x) => x,
            _ => self.intern(Node::Neg(a)),
        }
    }

    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => return self.num(x * y),
            (Some(0.0), _) | (_, Some(0.0)) => return self.num(0.0),
            (Some(1.0), None) => return b,
            (None, Some(1.0)) => return a,
            (Some(-1.0), None) => return self.neg(b),
            (None, Some(-1.0)) => return self.neg(a),
            _ => {}
        }
        // Pull negations out so that −x·y and x·(−y) share the node x·y.
        match (self.node(a), self.node(b)) {
            (Node::Neg(x), Node::Neg(y)) => return self.mul(x, y),
            (Node::Neg(x), _) => {
                let p = self.mul(x, b);
                return self.neg(p);
            }
            (_, Node::Neg(y)) => {
                let p = self.mul(a, y);
                return self.neg(p);
            }
            _ => {}
        }
        if let Some(c) = self.as_const(a) {
            if c < 0.0 {
                let m = self.num(-c);
                let p = self.mul(m, b);
                return self.neg(p);
            }
        }
        if let Some(c) = self.as_const(b) {
            if c < 0.0 {
                let m = self.num(-c);
                let p = self.mul(a, m);
                return self.neg(p);
            }
        }
        // c1 · (c2 · x) = (c1 c2) · x
        if let Some(c1) = self.as_const(a).or(self.as_const(b)) {
            let other = if self.as_const(a).is_some() { b } else { a };
            if let Node::Mul(p, r) = self.node(other) {
                let (c2, rest) = match (self.as_const(p), self.as_const(r)) {
                    (Some(c2), _) => (Some(c2), r),
                    (_, Some(c2)) => (Some(c2), p),
                    _ => (None, r),
                };
                if let Some(c2) = c2 {
                    let c = self.num(c1 * c2);
                    return self.mul(c, rest);
                }
            }
        }
        if a == b {
            return self.powi(a, 2);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Mul(a, b))
    }

    pub fn div(&mut self, a: Id, b: Id) -> Id {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) if y != 0.0 => return self.num(x / y),
            (Some(0.0), _) => return self.num(0.0),
            (None, Some(1.0)) => return a,
            (None, Some(-1.0)) => return self.neg(a),
            _ => {}
        }
        if a == b {
            return self.num(1.0);
        }
        match (self.node(a), self.node(b)) {
            (Node::Neg(x), Node::Neg(y)) => self.div(x, y),
            (Node::Neg(x), _) => {
                let q = self.div(x, b);
                self.neg(q)
            }
            (_, Node::Neg(y)) => {
                let q = self.div(a, y);
                self.neg(q)
            }
            _ => self.intern(Node::Div(a, b)),
        }
    }

    pub fn powi(&mut self, a: Id, n: i32) -> Id {
        if n == 0 {
            return self.num(1.0);
        }
        if n == 1 {
            return a;
        }
        if let Some(x) = self.as_const(a) {
            return self.num(x.powi(n));
        }
        match self.node(a) {
            // (−x)^n = ±x^n
            Node::Neg(x) => {
                let p = self.powi(x, n);
                if n % 2 == 0 {
                    p
                } else {
                    self.neg(p)
                }
            }
            Node::PowI(x, m) => match m.checked_mul(n) {
                Some(mn) => self.powi(x, mn),
                None => self.intern(Node::PowI(a, n)),
            },
            _ => self.intern(Node::PowI(a, n)),
        }
    }

    /// `a^b`; an integer-valued constant exponent becomes [`Node::PowI`].
    pub fn pow(&mut self, a: Id, b: Id) -> Id {
        if let Some(e) = self.as_const(b) {
            if e.fract() == 0.0 && e.abs() <= i32::MAX as f64 {
                return self.powi(a, e as i32);
            }
            if e == 0.5 {
                return self.call(Func::Sqrt, a);
            }
            if let Some(x) = self.as_const(a) {
                return self.num(x.powf(e));
            }
        }
        self.intern(Node::Pow(a, b))
    }

    pub fn call(&mut self, f: Func, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.num(f.apply(x));
        }
        match (f, self.node(a)) {
            // odd functions of a negation
            (Func::Sin | Func::Tan | Func::Asin | Func::Atan, Node::Neg(x)) => {
                let y = self.call(f, x);
                self.neg(y)
            }
            (Func::Cos, Node::Neg(x)) => self.call(Func::Cos, x),
            _ => self.intern(Node::Call(f, a)),
        }
    }

    pub fn atan2(&mut self, y: Id, x: Id) -> Id {
        if let (Some(a), Some(b)) = (self.as_const(y), self.as_const(x)) {
            return self.num(a.atan2(b));
        }
        self.intern(Node::Atan2(y, x))
    }

    /// `if a cmp b { x } else { y }`.
    pub fn select(&mut self, cmp: Cmp, a: Id, b: Id, x: Id, y: Id) -> Id {
        if x == y {
            return x;
        }
        if let (Some(a), Some(b)) = (self.as_const(a), self.as_const(b)) {
            return if cmp.holds(a, b) { x } else { y };
        }
        self.intern(Node::Select(cmp, a, b, x, y))
    }

    /// |a| = `if a >= 0 { a } else { −a }`: the derivative at 0 is +1 (right-sided).
    pub fn abs(&mut self, a: Id) -> Id {
        let zero = self.num(0.0);
        let na = self.neg(a);
        self.select(Cmp::Ge, a, zero, a, na)
    }

    /// 1 for a > 0, −1 for a < 0, 0 at 0; its derivative is 0 everywhere.
    pub fn sign(&mut self, a: Id) -> Id {
        let (zero, one, minus) = (self.num(0.0), self.num(1.0), self.num(-1.0));
        let below = self.select(Cmp::Gt, zero, a, minus, zero);
        self.select(Cmp::Gt, a, zero, one, below)
    }

    /// `if a >= b { a } else { b }`: at a tie, the derivative of `a`.
    pub fn max(&mut self, a: Id, b: Id) -> Id {
        self.select(Cmp::Ge, a, b, a, b)
    }

    /// `if b >= a { a } else { b }`: at a tie, the derivative of `a`.
    pub fn min(&mut self, a: Id, b: Id) -> Id {
        self.select(Cmp::Ge, b, a, a, b)
    }

    /// `if lo > x { lo } else if x > hi { hi } else { x }`: at either bound, the derivative of `x`.
    pub fn clamp(&mut self, x: Id, lo: Id, hi: Id) -> Id {
        let upper = self.select(Cmp::Gt, x, hi, hi, x);
        self.select(Cmp::Gt, lo, x, lo, upper)
    }

    /// The derivative of `root` along a direction: every variable `v` moves with speed
    /// `seed(v)` (an existing node id, or `None` for 0). With `seed = [v ↦ 1]` this is the partial
    /// derivative ∂root/∂v; with `seed(q_i) = q̇_i`, `seed(t) = 1` it is the total time
    /// derivative with q̈ = 0. `memo` caches results per node for this seed only.
    pub fn directional(&mut self, root: Id, seed: &dyn Fn(Var) -> Option<Id>, memo: &mut HashMap<Id, Id>) -> Id {
        if let Some(&d) = memo.get(&root) {
            return d;
        }
        for id in self.post_order(root, |id| memo.contains_key(&id)) {
            let d = self.derivative_rule(id, seed, memo);
            memo.insert(id, d);
        }
        memo[&root]
    }

    /// The nodes `root` reaches that `done` does not hold, each once, children before parents.
    /// Iterative: mechanisms make deep graphs (long chains of sums).
    pub fn post_order(&self, root: Id, done: impl Fn(Id) -> bool) -> Vec<Id> {
        let (mut order, mut seen) = (Vec::new(), HashSet::new());
        let mut stack = vec![(root, false)];
        while let Some((id, children_done)) = stack.pop() {
            if done(id) {
                continue;
            }
            if children_done {
                order.push(id);
            } else if seen.insert(id) {
                stack.push((id, true));
                stack.extend(self.children(id).into_iter().flatten().filter(|&c| !done(c) && !seen.contains(&c)).map(|c| (c, false)));
            }
        }
        order
    }

    /// Children of a node (at most four).
    pub fn children(&self, id: Id) -> [Option<Id>; 4] {
        match self.node(id) {
            Node::Const(_) | Node::Var(_) => [None; 4],
            Node::Neg(a) | Node::PowI(a, _) | Node::Call(_, a) => [Some(a), None, None, None],
            Node::Add(a, b) | Node::Mul(a, b) | Node::Div(a, b) | Node::Pow(a, b) | Node::Atan2(a, b) => [Some(a), Some(b), None, None],
            Node::Select(_, a, b, x, y) => [Some(a), Some(b), Some(x), Some(y)],
        }
    }

    /// d(id) from the (already memoized) derivatives of its children.
    fn derivative_rule(&mut self, id: Id, seed: &dyn Fn(Var) -> Option<Id>, memo: &HashMap<Id, Id>) -> Id {
        let d = |c: Id| memo[&c];
        match self.node(id) {
            Node::Const(_) => self.num(0.0),
            Node::Var(v) => match seed(v) {
                Some(s) => s,
                None => self.num(0.0),
            },
            Node::Add(a, b) => self.add(d(a), d(b)),
            Node::Neg(a) => self.neg(d(a)),
            Node::Mul(a, b) => {
                let l = self.mul(d(a), b);
                let r = self.mul(a, d(b));
                self.add(l, r)
            }
            // d(a/b) = (da − (a/b)·db) / b
            Node::Div(a, b) => {
                let t = self.mul(id, d(b));
                let n = self.sub(d(a), t);
                self.div(n, b)
            }
            // d(aⁿ) = n aⁿ⁻¹ da
            Node::PowI(a, n) => {
                let p = self.powi(a, n - 1);
                let c = self.num(n as f64);
                let cp = self.mul(c, p);
                self.mul(cp, d(a))
            }
            // d(aᵇ) = b aᵇ⁻¹ da for a constant exponent: finite at a = 0 for b ≥ 1, where the
            // general form below is 0·∞ (a contact force k·max(δ, 0)^1.5 at first touch)
            Node::Pow(a, b) if self.is_zero(d(b)) => {
                let one = self.num(1.0);
                let b1 = self.sub(b, one);
                let p = self.pow(a, b1);
                let bp = self.mul(b, p);
                self.mul(bp, d(a))
            }
            // d(aᵇ) = aᵇ (db ln a + b da / a)
            Node::Pow(a, b) => {
                let ln_a = self.call(Func::Ln, a);
                let t1 = self.mul(d(b), ln_a);
                let bda = self.mul(b, d(a));
                let t2 = self.div(bda, a);
                let s = self.add(t1, t2);
                self.mul(id, s)
            }
            Node::Call(f, a) => {
                let da = d(a);
                if self.is_zero(da) {
                    return da;
                }
                let factor = match f {
                    Func::Sin => self.call(Func::Cos, a),
                    Func::Cos => {
                        let s = self.call(Func::Sin, a);
                        self.neg(s)
                    }
                    // 1 + tan²
                    Func::Tan => {
                        let one = self.num(1.0);
                        let sq = self.powi(id, 2);
                        self.add(one, sq)
                    }
                    // ±1/√(1 − a²)
                    Func::Asin | Func::Acos => {
                        let one = self.num(1.0);
                        let sq = self.powi(a, 2);
                        let r = self.sub(one, sq);
                        let s = self.call(Func::Sqrt, r);
                        let inv = self.div(one, s);
                        if f == Func::Acos {
                            self.neg(inv)
                        } else {
                            inv
                        }
                    }
                    // 1/(1 + a²)
                    Func::Atan => {
                        let one = self.num(1.0);
                        let sq = self.powi(a, 2);
                        let den = self.add(one, sq);
                        self.div(one, den)
                    }
                    // 1/(2√a)
                    Func::Sqrt => {
                        let two = self.num(2.0);
                        let den = self.mul(two, id);
                        let one = self.num(1.0);
                        self.div(one, den)
                    }
                    Func::Exp => id,
                    // 1/a
                    Func::Ln => {
                        let one = self.num(1.0);
                        self.div(one, a)
                    }
                };
                self.mul(factor, da)
            }
            // d atan2(y, x) = (x dy − y dx) / (x² + y²)
            Node::Atan2(y, x) => {
                let xdy = self.mul(x, d(y));
                let ydx = self.mul(y, d(x));
                let n = self.sub(xdy, ydx);
                let x2 = self.powi(x, 2);
                let y2 = self.powi(y, 2);
                let den = self.add(x2, y2);
                self.div(n, den)
            }
            // the derivative of the branch taken, under the same comparison
            Node::Select(cmp, a, b, x, y) => self.select(cmp, a, b, d(x), d(y)),
        }
    }

    /// A node of another graph copied into this one, each of its variables replaced by the node
    /// `var` gives (folding what the substitution makes constant). `memo` maps `other`'s nodes
    /// already copied, for one `var`.
    pub fn import(&mut self, other: &Graph, root: Id, var: &dyn Fn(&mut Graph, Var) -> Id, memo: &mut HashMap<Id, Id>) -> Id {
        for id in other.post_order(root, |id| memo.contains_key(&id)) {
            let c = |x: Id| memo[&x];
            let copy = match other.node(id) {
                Node::Const(bits) => self.num(f64::from_bits(bits)),
                Node::Var(v) => var(self, v),
                Node::Add(a, b) => self.add(c(a), c(b)),
                Node::Mul(a, b) => self.mul(c(a), c(b)),
                Node::Neg(a) => self.neg(c(a)),
                Node::Div(a, b) => self.div(c(a), c(b)),
                Node::PowI(a, n) => self.powi(c(a), n),
                Node::Pow(a, b) => self.pow(c(a), c(b)),
                Node::Call(f, a) => self.call(f, c(a)),
                Node::Atan2(y, x) => self.atan2(c(y), c(x)),
                Node::Select(cmp, a, b, x, y) => self.select(cmp, c(a), c(b), c(x), c(y)),
            };
            memo.insert(id, copy);
        }
        memo[&root]
    }

    /// ∂root/∂v.
    pub fn diff(&mut self, root: Id, v: Var, memo: &mut HashMap<Id, Id>) -> Id {
        let one = self.num(1.0);
        self.directional(root, &|w| (w == v).then_some(one), memo)
    }

    /// ∂root/∂v, remembering the partial of every node it passes for the next call by v.
    pub fn partial(&mut self, root: Id, v: Var) -> Id {
        let mut memo = self.partials.remove(&v).unwrap_or_default();
        let d = self.diff(root, v, &mut memo);
        self.partials.insert(v, memo);
        d
    }

    /// Forgets the partials [`Graph::partial`] remembered (their memory, once no more are taken).
    pub fn forget_partials(&mut self) {
        self.partials = HashMap::new();
    }

    /// Evaluates a node for given variable values.
    pub fn eval(&self, root: Id, value: &dyn Fn(Var) -> f64) -> f64 {
        let mut memo: HashMap<Id, f64> = HashMap::new();
        self.eval_memo(root, value, &mut memo)
    }

    /// Evaluates several nodes sharing one cache.
    pub fn eval_memo(&self, root: Id, value: &dyn Fn(Var) -> f64, memo: &mut HashMap<Id, f64>) -> f64 {
        for id in self.post_order(root, |id| memo.contains_key(&id)) {
            let v = |c: Id| memo[&c];
            let x = match self.node(id) {
                Node::Const(bits) => f64::from_bits(bits),
                Node::Var(var) => value(var),
                Node::Add(a, b) => v(a) + v(b),
                Node::Mul(a, b) => v(a) * v(b),
                Node::Neg(a) => -v(a),
                Node::Div(a, b) => v(a) / v(b),
                Node::PowI(a, n) => v(a).powi(n),
                Node::Pow(a, b) => v(a).powf(v(b)),
                Node::Call(f, a) => f.apply(v(a)),
                Node::Atan2(y, x) => v(y).atan2(v(x)),
                Node::Select(cmp, a, b, x, y) => {
                    if cmp.holds(v(a), v(b)) {
                        v(x)
                    } else {
                        v(y)
                    }
                }
            };
            memo.insert(id, x);
        }
        memo[&root]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift64*): tests must be reproducible.
    pub(crate) struct Rng(u64);
    impl Rng {
        pub(crate) fn new(seed: u64) -> Self {
            Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
        }
        /// Uniform in [lo, hi).
        pub(crate) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            let u = (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64;
            lo + (hi - lo) * u
        }
    }

    fn env(vals: &[f64]) -> impl Fn(Var) -> f64 + '_ {
        move |v| match v {
            Var::Q(i) => vals[i as usize],
            Var::T => vals[3],
            _ => 0.0,
        }
    }

    /// Builds f(q0, q1, q2, t) exercising every node kind; arguments stay in every function's domain
    /// for q ∈ [0.1, 0.6], t ∈ [0, 1].
    fn every_kind(g: &mut Graph) -> Id {
        let x = g.var(Var::Q(0));
        let y = g.var(Var::Q(1));
        let z = g.var(Var::Q(2));
        let t = g.var(Var::T);
        let s = g.call(Func::Sin, x);
        let c = g.call(Func::Cos, y);
        let tn = g.call(Func::Tan, z);
        let as_ = g.call(Func::Asin, x);
        let ac = g.call(Func::Acos, y);
        let at = g.call(Func::Atan, t);
        let sq = g.call(Func::Sqrt, z);
        let ex = g.call(Func::Exp, t);
        let ln = g.call(Func::Ln, x);
        let a2 = g.atan2(y, x);
        let p = g.pow(z, t); // z^t
        let p3 = g.powi(y, 3);
        let d = g.div(s, c);
        let mut acc = g.mul(d, tn);
        for term in [as_, ac, at, sq, ex, ln, a2, p, p3] {
            let m = g.mul(term, x);
            acc = g.add(acc, m);
        }
        let n = g.neg(acc);
        g.sub(n, t)
    }

    /// Exact derivatives against central differences at random points. The step h = 1e-5 gives a
    /// truncation error O(h²·f''') ≈ 1e-10 and a rounding error O(ε·|f|/h) ≈ 1e-11 for |f| = O(1–10),
    /// so agreement to 1e-7 (relative to max(1, |f'|)) is a real check, not a tautology.
    #[test]
    fn derivatives_match_central_differences() {
        let mut g = Graph::new();
        let f = every_kind(&mut g);
        let mut rng = Rng::new(7);
        let vars = [Var::Q(0), Var::Q(1), Var::Q(2), Var::T];
        let derivs: Vec<Id> = vars
            .iter()
            .map(|&v| {
                let mut memo = HashMap::new();
                g.diff(f, v, &mut memo)
            })
            .collect();
        for _ in 0..200 {
            let p = [rng.uniform(0.1, 0.6), rng.uniform(0.1, 0.6), rng.uniform(0.1, 0.6), rng.uniform(0.0, 1.0)];
            for (k, &dk) in derivs.iter().enumerate() {
                let h = 1e-5;
                let (mut a, mut b) = (p, p);
                a[k] += h;
                b[k] -= h;
                let fd = (g.eval(f, &env(&a)) - g.eval(f, &env(&b))) / (2.0 * h);
                let exact = g.eval(dk, &env(&p));
                assert!((fd - exact).abs() <= 1e-7 * exact.abs().max(1.0), "d/d{:?}: exact {exact}, central difference {fd}", vars[k]);
            }
        }
    }

    /// The total time derivative (seed q ↦ q̇, t ↦ 1) equals Σ ∂f/∂qᵢ q̇ᵢ + ∂f/∂t.
    #[test]
    fn directional_derivative_is_the_chain_rule() {
        let mut g = Graph::new();
        let f = every_kind(&mut g);
        let qd: Vec<Id> = (0..3).map(|i| g.var(Var::Qd(i))).collect();
        let one = g.num(1.0);
        let seed = |v: Var| match v {
            Var::Q(i) => Some(qd[i as usize]),
            Var::T => Some(one),
            _ => None,
        };
        let mut memo = HashMap::new();
        let total = g.directional(f, &seed, &mut memo);
        let partials: Vec<Id> = [Var::Q(0), Var::Q(1), Var::Q(2), Var::T]
            .iter()
            .map(|&v| {
                let mut m = HashMap::new();
                g.diff(f, v, &mut m)
            })
            .collect();
        let mut rng = Rng::new(11);
        for _ in 0..100 {
            let p: Vec<f64> = (0..4).map(|i| if i < 3 { rng.uniform(0.1, 0.6) } else { rng.uniform(0.0, 1.0) }).collect();
            let v: Vec<f64> = (0..3).map(|_| rng.uniform(-2.0, 2.0)).collect();
            let value = |var: Var| match var {
                Var::Q(i) => p[i as usize],
                Var::Qd(i) => v[i as usize],
                Var::T => p[3],
                Var::Param(_) | Var::Lambda(_) | Var::Dir(_) => 0.0,
            };
            let chain: f64 = (0..3).map(|i| g.eval(partials[i], &value) * v[i]).sum::<f64>() + g.eval(partials[3], &value);
            let direct = g.eval(total, &value);
            // Same arithmetic in another order: agreement to rounding (1e-12 relative).
            assert!((chain - direct).abs() <= 1e-12 * chain.abs().max(1.0), "{chain} vs {direct}");
        }
    }

    /// The non-smooth functions: values, and derivatives against central differences away from
    /// their kinks (h = 1e-6 and points at least 1e-3 from a kink, so a difference never straddles
    /// one; the functions are piecewise linear or polynomial there, so 1e-7 is a real check).
    #[test]
    fn kinks_away_from_the_kink() {
        let mut g = Graph::new();
        let x = g.var(Var::Q(0));
        let y = g.var(Var::Q(1));
        let (lo, hi) = (g.num(-0.5), g.num(0.5));
        let x3 = g.powi(x, 3);
        let xy = g.mul(x, y);
        let fs = [g.abs(x3), g.sign(x), g.min(x3, xy), g.max(x3, xy), g.clamp(x3, lo, hi), g.select(Cmp::Gt, x, y, x3, xy)];
        let value = |x: f64, y: f64| {
            let (x3, xy) = (x.powi(3), x * y);
            [x3.abs(), if x > 0.0 { 1.0 } else { -1.0 }, x3.min(xy), x3.max(xy), x3.clamp(-0.5, 0.5), if x > y { x3 } else { xy }]
        };
        let mut rng = Rng::new(5);
        let mut checked = 0;
        while checked < 300 {
            let (px, py) = (rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2));
            let kinks = [px, px.powi(3) - px * py, px.powi(3) - 0.5, px.powi(3) + 0.5, px - py];
            if kinks.iter().any(|k| k.abs() < 1e-3) {
                continue;
            }
            checked += 1;
            let env = |x: f64, y: f64| move |v: Var| if v == Var::Q(0) { x } else { y };
            for (k, &f) in fs.iter().enumerate() {
                assert_eq!(g.eval(f, &env(px, py)), value(px, py)[k], "function {k} at ({px}, {py})");
                let mut memo = HashMap::new();
                let df = g.diff(f, Var::Q(0), &mut memo);
                let h = 1e-6;
                let fd = (value(px + h, py)[k] - value(px - h, py)[k]) / (2.0 * h);
                let exact = g.eval(df, &env(px, py));
                assert!((fd - exact).abs() <= 1e-7, "d/dx of function {k} at ({px}, {py}): exact {exact}, difference {fd}");
            }
        }
    }

    /// At the kink itself, every derivative is finite and is the documented one-sided value:
    /// the derivative of the branch the value takes.
    #[test]
    fn kinks_at_the_kink() {
        let mut g = Graph::new();
        let x = g.var(Var::Q(0));
        let zero = g.num(0.0);
        let one = g.num(1.0);
        let two_x = g.add(x, x);
        let at_zero = |_: Var| 0.0;
        let d = |g: &mut Graph, f: Id| {
            let mut memo = HashMap::new();
            let df = g.diff(f, Var::Q(0), &mut memo);
            g.eval(df, &at_zero)
        };
        let cases = [
            (g.abs(x), 1.0, "abs: x ≥ 0 takes x"),
            (g.sign(x), 0.0, "sign: constant on each side"),
            (g.max(two_x, x), 2.0, "max(a, b) at a tie: a"),
            (g.min(two_x, x), 2.0, "min(a, b) at a tie: a"),
            (g.clamp(two_x, zero, one), 2.0, "clamp at its lower bound: the inside"),
            (g.select(Cmp::Gt, x, zero, two_x, x), 1.0, "`>` at a tie: else"),
            (g.select(Cmp::Ge, x, zero, two_x, x), 2.0, "`>=` at a tie: then"),
        ];
        for (f, expected, what) in cases {
            assert_eq!(d(&mut g, f), expected, "{what}");
        }
        // A Hertz-like contact force max(x, 0)^1.5: the constant-exponent rule gives 0 at first
        // touch, where aᵇ(b·da/a) would be 0·∞ = NaN.
        let m = g.max(x, zero);
        let e = g.num(1.5);
        let f = g.pow(m, e);
        assert_eq!(d(&mut g, f), 0.0);
        // and its second derivative 0.75·x^-0.5 is +∞ at 0 — honestly infinite, not NaN
        let mut memo = HashMap::new();
        let df = g.diff(f, Var::Q(0), &mut memo);
        let mut memo = HashMap::new();
        let ddf = g.diff(df, Var::Q(0), &mut memo);
        assert_eq!(g.eval(ddf, &at_zero), f64::INFINITY);
    }

    #[test]
    fn simplification_identities() {
        let mut g = Graph::new();
        let x = g.var(Var::Q(0));
        let y = g.var(Var::Q(1));
        let zero = g.num(0.0);
        let one = g.num(1.0);
        assert_eq!(g.add(x, zero), x);
        assert_eq!(g.mul(x, one), x);
        let x0 = g.mul(x, zero);
        assert!(g.is_zero(x0));
        let xmx = g.sub(x, x);
        assert!(g.is_zero(xmx));
        let nx = g.neg(x);
        assert_eq!(g.neg(nx), x);
        assert_eq!(g.add(x, y), g.add(y, x), "addition is hash-consed commutatively");
        assert_eq!(g.mul(x, y), g.mul(y, x), "multiplication is hash-consed commutatively");
        // Negations are pulled out so −x·y and x·(−y) share one product node.
        let ny = g.neg(y);
        let a = g.mul(nx, y);
        let b = g.mul(x, ny);
        assert_eq!(a, b);
        // Constants fold, through nested products too: 2·(3·x) = 6·x.
        let two = g.num(2.0);
        let three = g.num(3.0);
        let three_x = g.mul(three, x);
        let six = g.num(6.0);
        assert_eq!(g.mul(two, three_x), g.mul(six, x));
        let s = g.call(Func::Sin, zero);
        assert!(g.is_zero(s));
        // x·x is x², and (x²)³ = x⁶
        let sq = g.mul(x, x);
        assert_eq!(g.node(sq), Node::PowI(x, 2));
        let sq3 = g.powi(sq, 3);
        assert_eq!(g.node(sq3), Node::PowI(x, 6));
        // sin(x) built twice is one node: the basis of common-subexpression elimination.
        assert_eq!(g.call(Func::Sin, x), g.call(Func::Sin, x));
        assert_eq!(g.div(x, x), one);
        // cos(−x) = cos x
        let cnx = g.call(Func::Cos, nx);
        assert_eq!(cnx, g.call(Func::Cos, x));
    }
}
