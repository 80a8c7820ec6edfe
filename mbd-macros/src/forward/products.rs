//! Products with D, Dᵀ and M⁻¹, straight-line over their compile-time patterns: the statements
//! every solve of the forward dynamics is written with.

use proc_macro2::TokenStream;
use quote::quote;

use super::Plan;
use crate::emit::{usize_lit, Output};
use crate::formulation::Formulation;

impl Plan<'_> {
    /// (D x)_r for a vector x, one expression per row.
    pub(super) fn row_times(&self, x: &TokenStream) -> Vec<TokenStream> {
        (0..self.nc)
            .map(|r| {
                let terms: Vec<TokenStream> = self
                    .pattern
                    .iter()
                    .enumerate()
                    .filter(|(_, &(row, _))| row == r)
                    .map(|(k, &(_, c))| {
                        let (k, c) = (usize_lit(k), usize_lit(c));
                        quote!(jv[#k] * #x[#c])
                    })
                    .collect();
                if terms.is_empty() {
                    self.zero.clone()
                } else {
                    quote!((#(#terms)+*))
                }
            })
            .collect()
    }

    /// (Dᵀ y)_c; None for a column without non-zeros.
    pub(super) fn transpose_column(&self, y: &TokenStream, c: usize) -> Option<TokenStream> {
        let terms: Vec<TokenStream> = self
            .pattern
            .iter()
            .enumerate()
            .filter(|(_, &(_, col))| col == c)
            .map(|(k, &(r, _))| {
                let (k, r) = (usize_lit(k), usize_lit(r));
                quote!(jv[#k] * #y[#r])
            })
            .collect();
        (!terms.is_empty()).then(|| quote!((#(#terms)+*)))
    }

    /// x[c] += (M⁻¹ w)_c (or another assignment `sign`) for w given per column (`w(c)`), over
    /// M⁻¹'s structural non-zeros.
    pub(super) fn add_minv(&self, x: &TokenStream, sign: &TokenStream, w: &dyn Fn(usize) -> Option<TokenStream>) -> Vec<TokenStream> {
        (0..self.nv)
            .filter_map(|c| {
                let cl = usize_lit(c);
                let mut terms: Vec<TokenStream> = w(c).map(|wc| quote!(minv[#cl] * #wc)).into_iter().collect();
                for (k, &(r, c2)) in self.coupling.iter().enumerate() {
                    if r == c {
                        if let Some(wc2) = w(c2) {
                            let kl = usize_lit(k);
                            terms.push(quote!(minv_off[#kl] * #wc2));
                        }
                    }
                }
                (!terms.is_empty()).then(|| quote!(#x[#cl] #sign #(#terms)+*;))
            })
            .collect()
    }

    /// x[c] += (M⁻¹ Dᵀ y)_c; with M⁻¹ coupled, Dᵀy is formed first.
    pub(super) fn add_transpose(&self, x: &TokenStream, y: &TokenStream, sign: TokenStream) -> Vec<TokenStream> {
        if !self.coupled() {
            return self.add_minv(x, &sign, &|c| self.transpose_column(y, c));
        }
        let columns: Vec<TokenStream> = (0..self.nv)
            .filter_map(|c| {
                let cl = usize_lit(c);
                self.transpose_column(y, c).map(|t| quote!(w[#cl] = #t;))
            })
            .collect();
        let has = |c: usize| self.transpose_column(y, c).is_some();
        let (zero, nv_l) = (&self.zero, &self.nv_l);
        let mut out = vec![quote!(let mut w = [#zero; #nv_l]; #(#columns)*)];
        out.extend(self.add_minv(x, &sign, &|c| {
            let cl = usize_lit(c);
            has(c).then(|| quote!(w[#cl]))
        }));
        out
    }

    /// M⁻¹ from the evaluated mass: `minv[c]` on the diagonal — 1/M_cc, once per distinct mass
    /// expression, or from a block with products of inertia, evaluated inverted in `mi` — and
    /// `minv_off[k]` off it.
    pub(super) fn inverse_mass(&self) -> (Vec<TokenStream>, Vec<TokenStream>) {
        let f = self.f;
        let one = &self.one;
        let mut minv = Vec::new();
        let mut minv_off = Vec::new();
        for (k, &(r, c, _)) in f.mass_inverse.iter().enumerate() {
            let (kl, rl) = (usize_lit(k), usize_lit(r));
            if r == c {
                minv.push(quote!(minv[#rl] = mi[#kl];));
            } else {
                let index = usize_lit(minv_off.len());
                minv_off.push(quote!(minv_off[#index] = mi[#kl];));
            }
        }
        let from_block = |i: usize| f.mass_inverse.iter().any(|e| e.0 == i && e.1 == i);
        for (i, &node) in f.mass.iter().enumerate() {
            let il = usize_lit(i);
            if from_block(i) {
                continue;
            }
            match (0..i).find(|&j| f.mass[j] == node && !from_block(j)) {
                Some(j) => {
                    let jl = usize_lit(j);
                    minv.push(quote!(minv[#il] = minv[#jl];));
                }
                None => minv.push(quote!(minv[#il] = #one / m[#il];)),
            }
        }
        (minv, minv_off)
    }
}

/// Outputs `mi[k]` = the k-th structural non-zero of the coupled blocks of M⁻¹ (none for a
/// diagonal M).
pub(super) fn inverse_outputs(f: &Formulation) -> Vec<Output> {
    f.mass_inverse
        .iter()
        .enumerate()
        .map(|(k, &(_, _, node))| {
            let k = usize_lit(k);
            Output { target: quote!(mi[#k]), node }
        })
        .collect()
}
