//! One value of `frame.settings`, typed as what it is: a count is an integer, a flag a bool, a
//! time a float, a list of per-light budgets a list; text only where the value is a name (a
//! method, a choice, an adapter). Python receives the same types (int, float, bool, str, list,
//! dict, None), so nobody compares against `"0"` or splits `"0+0+0+256+0+0"`.

use std::borrow::Cow;
use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub enum Setting {
    Int(i64),
    Float(f64),
    Bool(bool),
    Text(Cow<'static, str>),
    List(Vec<Setting>),
    /// Named fields, in order (a dict in Python).
    Record(Vec<(&'static str, Setting)>),
    /// Nothing applies (e.g. the RSM frame of a light that is not a spot light); None in Python.
    Absent,
}

impl Setting {
    /// The text of a [`Setting::Text`], else `None`.
    pub fn as_text(&self) -> Option<&str> {
        match self {
            Setting::Text(t) => Some(t),
            _ => None,
        }
    }
}

/// For logs and Rust callers: numbers and names as written, lists in brackets.
impl fmt::Display for Setting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Setting::Int(v) => write!(f, "{v}"),
            Setting::Float(v) => write!(f, "{v}"),
            Setting::Bool(v) => write!(f, "{v}"),
            Setting::Text(v) => write!(f, "{v}"),
            Setting::List(items) => {
                write!(f, "[")?;
                for (i, item) in items.iter().enumerate() {
                    write!(f, "{}{item}", if i > 0 { ", " } else { "" })?;
                }
                write!(f, "]")
            }
            Setting::Record(fields) => {
                write!(f, "{{")?;
                for (i, (name, value)) in fields.iter().enumerate() {
                    write!(f, "{}{name}: {value}", if i > 0 { ", " } else { "" })?;
                }
                write!(f, "}}")
            }
            Setting::Absent => write!(f, "none"),
        }
    }
}

macro_rules! int_setting {
    ($($ty:ty),+) => {
        $(impl From<$ty> for Setting {
            fn from(v: $ty) -> Self {
                Setting::Int(v as i64)
            }
        })+
    };
}
int_setting!(i64, u32, u64, usize);

impl From<f64> for Setting {
    fn from(v: f64) -> Self {
        Setting::Float(v)
    }
}
impl From<f32> for Setting {
    fn from(v: f32) -> Self {
        Setting::Float(v as f64)
    }
}
impl From<bool> for Setting {
    fn from(v: bool) -> Self {
        Setting::Bool(v)
    }
}
impl From<&'static str> for Setting {
    fn from(v: &'static str) -> Self {
        Setting::Text(Cow::Borrowed(v))
    }
}
impl From<String> for Setting {
    fn from(v: String) -> Self {
        Setting::Text(Cow::Owned(v))
    }
}
impl<T: Into<Setting>> From<Vec<T>> for Setting {
    fn from(v: Vec<T>) -> Self {
        Setting::List(v.into_iter().map(Into::into).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::Setting;

    #[test]
    fn display_writes_each_type_as_written() {
        let lists: Setting = vec![vec![0u32, 0, 256], vec![7]].into();
        assert_eq!(lists.to_string(), "[[0, 0, 256], [7]]");
        let record = Setting::Record(vec![("tan", 0.5f64.into()), ("fit", "scene".into())]);
        assert_eq!(record.to_string(), "{tan: 0.5, fit: scene}");
        assert_eq!(Setting::from(true).to_string(), "true");
        assert_eq!(Setting::Absent.to_string(), "none");
    }
}
