//! Fixed-length arrays in scene files read strictly: serde's own arrays stop after `N` entries
//! and accept more, so `resolution = [64, 64, 64]` passed. These read every entry and refuse a
//! length other than `N`, naming it.

use serde::de::{Deserialize, Deserializer, Error};

/// `[T; N]`, exactly `N` entries.
pub fn array<'de, D, T, const N: usize>(d: D) -> Result<[T; N], D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    let v = Vec::<T>::deserialize(d)?;
    let n = v.len();
    v.try_into()
        .map_err(|_| D::Error::invalid_length(n, &format!("exactly {N} entries").as_str()))
}

/// `Option<[T; N]>`, exactly `N` entries when given.
pub fn option<'de, D, T, const N: usize>(d: D) -> Result<Option<[T; N]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Option::<Vec<T>>::deserialize(d)?
        .map(|v| {
            let n = v.len();
            v.try_into()
                .map_err(|_| D::Error::invalid_length(n, &format!("exactly {N} entries").as_str()))
        })
        .transpose()
}
