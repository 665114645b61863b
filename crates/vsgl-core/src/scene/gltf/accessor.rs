//! Accessors: typed reads of vertex and index data out of checked bufferViews, with every
//! bound checked, sparse substitution, and the scene-wide caps on the geometry produced.

use gltf::json;
use json::accessor::{ComponentType, GenericComponentType, IndexComponentType, Type as AccType};
use json::validation::Checked;

use super::{Ctx, MAX_GEOMETRY_BYTES, MAX_UNBACKED_ELEMENTS};
use crate::error::Result;

/// How an accessor's components become output values.
pub(super) trait Component: Copy + Default {
    fn decode(bytes: &[u8], ct: ComponentType, normalized: bool) -> Option<Self>;
}

fn read_le<const N: usize>(bytes: &[u8]) -> Option<[u8; N]> {
    bytes.get(..N)?.try_into().ok()
}


/// What a sparse substitution needs of its accessor's elements: how many, their components,
/// the component type and whether integers are normalized.
#[derive(Clone, Copy)]
struct ElementLayout {
    count: u64,
    ncomp: usize,
    ct: ComponentType,
    normalized: bool,
}

impl Component for f32 {
    fn decode(b: &[u8], ct: ComponentType, normalized: bool) -> Option<f32> {
        Some(match ct {
            ComponentType::F32 => f32::from_le_bytes(read_le(b)?),
            ComponentType::I8 => {
                let v = f32::from(i8::from_le_bytes(read_le(b)?));
                if normalized {
                    (v / 127.0).max(-1.0)
                } else {
                    v
                }
            }
            ComponentType::U8 => {
                let v = f32::from(u8::from_le_bytes(read_le(b)?));
                if normalized {
                    v / 255.0
                } else {
                    v
                }
            }
            ComponentType::I16 => {
                let v = f32::from(i16::from_le_bytes(read_le(b)?));
                if normalized {
                    (v / 32767.0).max(-1.0)
                } else {
                    v
                }
            }
            ComponentType::U16 => {
                let v = f32::from(u16::from_le_bytes(read_le(b)?));
                if normalized {
                    v / 65535.0
                } else {
                    v
                }
            }
            ComponentType::U32 => {
                let v = u32::from_le_bytes(read_le(b)?) as f64;
                (if normalized { v / u32::MAX as f64 } else { v }) as f32
            }
        })
    }
}

impl Component for u32 {
    fn decode(b: &[u8], ct: ComponentType, _normalized: bool) -> Option<u32> {
        match ct {
            ComponentType::U8 => Some(u32::from(u8::from_le_bytes(read_le(b)?))),
            ComponentType::U16 => Some(u32::from(u16::from_le_bytes(read_le(b)?))),
            ComponentType::U32 => Some(u32::from_le_bytes(read_le(b)?)),
            _ => None,
        }
    }
}

fn type_name(t: AccType) -> &'static str {
    match t {
        AccType::Scalar => "SCALAR",
        AccType::Vec2 => "VEC2",
        AccType::Vec3 => "VEC3",
        AccType::Vec4 => "VEC4",
        AccType::Mat2 => "MAT2",
        AccType::Mat3 => "MAT3",
        AccType::Mat4 => "MAT4",
    }
}

impl Ctx<'_> {
    pub(super) fn charge_geometry(&self, bytes: u64, element: &str) -> Result<()> {
        let total = self.geometry_bytes.get().saturating_add(bytes);
        if total > MAX_GEOMETRY_BYTES {
            return Err(self.err(
                element,
                format!("the scene's vertex and index data exceed the limit of {MAX_GEOMETRY_BYTES} bytes"),
            ));
        }
        self.geometry_bytes.set(total);
        Ok(())
    }

    /// Reads accessor `idx` as `count × multiplicity(ty)` values, with every bound checked.
    /// `used_as` names the referencing element (for messages).
    pub(super) fn read_accessor<T: Component>(
        &self,
        idx: usize,
        ty: AccType,
        used_as: &str,
        allowed: &[ComponentType],
    ) -> Result<Vec<T>> {
        let acc = self
            .root
            .accessors
            .get(idx)
            .ok_or_else(|| self.err(used_as, format!("accessors[{idx}] does not exist")))?;
        let el = format!("accessors[{idx}]");
        match acc.type_ {
            Checked::Valid(t) if t == ty => {}
            Checked::Valid(t) => {
                return Err(self.err(
                    el,
                    format!(
                        "type is {} but {used_as} needs {}",
                        type_name(t),
                        type_name(ty)
                    ),
                ))
            }
            Checked::Invalid => return Err(self.err(el, "invalid accessor type")),
        }
        let ct = match acc.component_type {
            Checked::Valid(GenericComponentType(ct)) => ct,
            Checked::Invalid => return Err(self.err(el, "invalid componentType")),
        };
        if !allowed.contains(&ct) {
            return Err(self.err(
                el,
                format!("componentType {ct:?} is not allowed for {used_as}"),
            ));
        }
        let ncomp = ty.multiplicity();
        let csize = ct.size();
        let elem = ncomp * csize;
        let count = acc.count.0;
        let values = count
            .checked_mul(ncomp as u64)
            .ok_or_else(|| self.err(el.clone(), format!("count {count} is too large")))?;
        let out_bytes = values.saturating_mul(std::mem::size_of::<T>() as u64);

        let mut out: Vec<T> = match acc.buffer_view {
            Some(v) => {
                let vi = v.value();
                let view = *self.views.get(vi).ok_or_else(|| {
                    self.err(
                        format!("{el}.bufferView"),
                        format!("bufferViews[{vi}] does not exist"),
                    )
                })?;
                let stride = view.stride.unwrap_or(elem);
                if stride < elem {
                    return Err(self.err(
                        el,
                        format!("bufferViews[{vi}].byteStride {stride} is smaller than the element size {elem}"),
                    ));
                }
                let offset = acc.byte_offset.map_or(0, |o| o.0);
                let need = if count == 0 {
                    Some(offset)
                } else {
                    (count - 1)
                        .checked_mul(stride as u64)
                        .and_then(|x| x.checked_add(offset))
                        .and_then(|x| x.checked_add(elem as u64))
                };
                let need = need.filter(|&n| n <= view.len as u64).ok_or_else(|| {
                    self.err(
                        el.clone(),
                        format!(
                            "out of bounds: byteOffset {offset} + byteStride {stride} × (count {count} − 1) + \
                             element size {elem} exceeds bufferViews[{vi}].byteLength {}",
                            view.len
                        ),
                    )
                })?;
                // Every element now lies inside the view, so `values` is bounded by the file.
                self.charge_geometry(out_bytes, &el)?;
                let data = self
                    .view_bytes(view)
                    .and_then(|d| d.get(offset as usize..need as usize))
                    .ok_or_else(|| self.err(el.clone(), "bufferView out of range"))?;
                let mut out = Vec::with_capacity(values as usize);
                for i in 0..count as usize {
                    let start = i * stride;
                    for c in 0..ncomp {
                        let s = start + c * csize;
                        let v = data
                            .get(s..)
                            .and_then(|b| T::decode(b, ct, acc.normalized))
                            .ok_or_else(|| self.err(el.clone(), "cannot decode element"))?;
                        out.push(v);
                    }
                }
                out
            }
            None => {
                let total = self.unbacked_elements.get().saturating_add(count);
                if total > MAX_UNBACKED_ELEMENTS {
                    return Err(self.err(
                        el,
                        format!(
                            "count {count} without a bufferView exceeds the limit of {MAX_UNBACKED_ELEMENTS} \
                             zero-filled elements"
                        ),
                    ));
                }
                self.unbacked_elements.set(total);
                self.charge_geometry(out_bytes, &el)?;
                vec![T::default(); values as usize]
            }
        };

        if let Some(sparse) = &acc.sparse {
            self.apply_sparse(&mut out, sparse, idx, ElementLayout { count, ncomp, ct, normalized: acc.normalized })?;
        }
        Ok(out)
    }

    fn apply_sparse<T: Component>(&self, out: &mut [T], sparse: &json::accessor::sparse::Sparse, idx: usize, layout: ElementLayout) -> Result<()> {
        let ElementLayout { count, ncomp, ct, normalized } = layout;
        let el = format!("accessors[{idx}].sparse");
        let n = sparse.count.0;
        if n > count {
            return Err(self.err(
                el,
                format!("sparse count {n} exceeds the accessor count {count}"),
            ));
        }
        let ict = match sparse.indices.component_type {
            Checked::Valid(IndexComponentType(c)) => c,
            Checked::Invalid => {
                return Err(self.err(format!("{el}.indices"), "invalid componentType"))
            }
        };
        let region = |view: json::Index<json::buffer::View>,
                      offset: u64,
                      elem: usize,
                      what: &str|
         -> Result<&[u8]> {
            let vi = view.value();
            let v = *self.views.get(vi).ok_or_else(|| {
                self.err(
                    format!("{el}.{what}"),
                    format!("bufferViews[{vi}] does not exist"),
                )
            })?;
            let end = n
                .checked_mul(elem as u64)
                .and_then(|x| x.checked_add(offset))
                .filter(|&e| e <= v.len as u64)
                .ok_or_else(|| {
                    self.err(
                        format!("{el}.{what}"),
                        format!("out of bounds of bufferViews[{vi}]"),
                    )
                })?;
            self.view_bytes(v)
                .and_then(|d| d.get(offset as usize..end as usize))
                .ok_or_else(|| self.err(format!("{el}.{what}"), "out of bounds"))
        };
        let isize_ = ict.size();
        let elem = ncomp * ct.size();
        let indices = region(
            sparse.indices.buffer_view,
            sparse.indices.byte_offset.0,
            isize_,
            "indices",
        )?;
        let values = region(
            sparse.values.buffer_view,
            sparse.values.byte_offset.0,
            elem,
            "values",
        )?;
        for k in 0..n as usize {
            let target = indices
                .get(k * isize_..)
                .and_then(|b| u32::decode(b, ict, false))
                .ok_or_else(|| self.err(format!("{el}.indices"), "cannot decode index"))?;
            if u64::from(target) >= count {
                return Err(self.err(
                    format!("{el}.indices"),
                    format!("index {target} is out of range (count {count})"),
                ));
            }
            for c in 0..ncomp {
                let v = values
                    .get(k * elem + c * ct.size()..)
                    .and_then(|b| T::decode(b, ct, normalized))
                    .ok_or_else(|| self.err(format!("{el}.values"), "cannot decode value"))?;
                if let Some(slot) = out.get_mut(target as usize * ncomp + c) {
                    *slot = v;
                }
            }
        }
        Ok(())
    }

    /// Reads a float attribute and checks that every value is finite.
    pub(super) fn read_floats(&self, idx: usize, ty: AccType, used_as: &str) -> Result<Vec<f32>> {
        use ComponentType::*;
        let v: Vec<f32> = self.read_accessor(idx, ty, used_as, &[F32, I8, U8, I16, U16])?;
        if let Some(pos) = v.iter().position(|x| !x.is_finite()) {
            return Err(self.err(
                format!("accessors[{idx}]"),
                format!(
                    "non-finite value in element {} (used as {used_as})",
                    pos / ty.multiplicity().max(1)
                ),
            ));
        }
        Ok(v)
    }
}
