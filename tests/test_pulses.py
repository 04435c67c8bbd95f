"""The pulse library against closed forms and independent numerical integration."""

import math

import numpy as np
import pytest
from scipy import integrate

from rockcli.errors import RockcliInputError
from rockcli.pulses import (
    PULSE_SHAPES,
    RICKER_ANTI_BETA,
    RICKER_ANTI_X_PEAK,
    OneCosine,
    OneSine,
    RickerAntisymmetric,
    RickerSymmetric,
    gaussian_derivative_peak_period,
    make_pulse,
    parse_pulse_spec,
)
from rockcli.io.units import G

ALL = [RickerSymmetric, RickerAntisymmetric, OneSine, OneCosine]
RICKERS = [RickerSymmetric, RickerAntisymmetric]


def test_beta_is_the_largest_value_of_the_antisymmetric_shape():
    x = np.linspace(-6.0, 6.0, 2_000_001)
    h = np.abs((x**2 - 3.0) * x * np.exp(-(x**2) / 2.0))
    assert RICKER_ANTI_BETA == pytest.approx(h.max(), rel=1e-11)
    assert x[np.argmax(h)] == pytest.approx(RICKER_ANTI_X_PEAK, abs=1e-5)
    assert round(RICKER_ANTI_BETA, 2) == 1.38  # the paper's rounded value
    # x_peak is a root of the derivative -x^4 + 6 x^2 - 3
    assert -RICKER_ANTI_X_PEAK**4 + 6 * RICKER_ANTI_X_PEAK**2 - 3 == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("a_p", [2.5, -0.7])
@pytest.mark.parametrize("T_p", [0.3, 2.0])
def test_antisymmetric_ricker_peaks_at_exactly_a_p_before_t0(a_p, T_p):
    p = RickerAntisymmetric(a_p, T_p, 4.0)
    t = np.linspace(*p.support(), 400_001)
    a = p.acceleration(t)
    i_max, i_min = np.argmax(a), np.argmin(a)
    # sampled extremes (grid step 1.5e-5 T_p) are within 1e-8 of +-a_p and never above
    assert max(a.max(), -a.min()) == pytest.approx(abs(a_p), rel=1e-8)
    assert max(a.max(), -a.min()) <= abs(a_p) * (1 + 1e-15)
    assert a.max() == pytest.approx(-a.min(), rel=1e-12)
    assert p.acceleration(p.t_peak) == pytest.approx(a_p, rel=1e-14)
    assert p.t_peak < p.t0
    # positive a_p: the positive lobe comes first; negative a_p reverses the order
    assert (t[i_max] < t[i_min]) == (a_p > 0)
    assert p.acceleration(p.t0) == 0.0


@pytest.mark.parametrize("a_p", [2.5, -0.7])
def test_symmetric_ricker_matches_eq5_and_peaks_at_t0(a_p):
    T_p, t0 = 0.8, 3.1
    p = RickerSymmetric(a_p, T_p, t0)
    t = np.linspace(*p.support(), 300_001)
    a = p.acceleration(t)
    tau = t - t0
    eq5 = a_p * (1 - 2 * math.pi**2 * tau**2 / T_p**2) * np.exp(-0.5 * 2 * math.pi**2 * tau**2 / T_p**2)
    assert np.max(np.abs(a - eq5)) <= 1e-14 * abs(a_p)
    assert p.acceleration(t0) == a_p
    assert np.max(np.abs(a)) == pytest.approx(abs(a_p), rel=1e-12)


def test_antisymmetric_ricker_matches_eq6():
    a_p, T_p, t0 = 1.7, 1.3, 5.0
    p = RickerAntisymmetric(a_p, T_p, t0)
    tau = np.linspace(-3 * T_p, 3 * T_p, 10001)
    eq6 = (a_p / RICKER_ANTI_BETA) * (4 * math.pi**2 * tau**2 / (3 * T_p**2) - 3) * (
        2 * math.pi * tau / (math.sqrt(3) * T_p)
    ) * np.exp(-0.5 * 4 * math.pi**2 * tau**2 / (3 * T_p**2))
    assert np.max(np.abs(p.acceleration(t0 + tau) - eq6)) <= 1e-14 * a_p


@pytest.mark.parametrize("cls", ALL)
def test_support_and_defaults(cls):
    p = cls(1.0, 0.5)
    s0, s1 = p.support()
    if cls in RICKERS:
        assert p.t0 == 1.5 and (s0, s1) == (0.0, 3.0)
    else:
        assert p.t0 == 0.0 and (s0, s1) == (0.0, 0.5)
    eps = 1e-9
    outside = np.array([s0 - 10, s0 - eps, s1 + eps, s1 + 10])
    assert np.all(p.acceleration(outside) == 0.0)
    inside = np.linspace(s0, s1, 101)[1:-1]
    assert np.count_nonzero(p.acceleration(inside)) >= 98
    assert p.omega_p == pytest.approx(2 * math.pi / 0.5)


def _quad(f, lo, hi, points, scale):
    pts = [x for x in points if lo < x < hi]
    val, err = integrate.quad(f, lo, hi, points=pts or None, limit=400, epsabs=1e-12 * scale, epsrel=1e-11)
    return val


@pytest.mark.parametrize("cls", ALL)
@pytest.mark.parametrize("a_p,T_p,t0", [(2.0, 0.7, 1.9), (-0.4, 3.0, 12.0)])
def test_velocity_and_displacement_are_exact_integrals(cls, a_p, T_p, t0):
    """v(t) = int a, d(t) = int (t - s) a(s) ds (Cauchy), from rest before the support."""
    p = cls(a_p, T_p, t0)
    s0, s1 = p.support()
    acc = lambda s: float(p.acceleration(s))
    kinks = [s0, p.t0, s1]
    times = np.concatenate([[s0 - 1.0, s0], np.linspace(s0, s1, 13)[1:-1], [s1, s1 + 2.5 * T_p]])
    scale_v = abs(a_p) * T_p
    scale_d = abs(a_p) * T_p**2
    for t in times:
        v_ref = _quad(acc, s0, min(t, s1), kinks, scale_v) if t > s0 else 0.0
        d_ref = _quad(lambda s: (t - s) * acc(s), s0, min(t, s1), kinks, scale_d) if t > s0 else 0.0
        assert p.velocity(t) == pytest.approx(v_ref, abs=1e-10 * scale_v)
        assert p.displacement(t) == pytest.approx(d_ref, abs=1e-10 * scale_d)
    # vectorised calls agree with scalar ones
    assert np.allclose(p.velocity(times), [p.velocity(t) for t in times], rtol=0, atol=1e-15 * scale_v)


@pytest.mark.parametrize("cls", ALL)
def test_derivatives_chain(cls):
    """d' = v and v' = a on a fine grid (central differences)."""
    p = cls(1.3, 0.9, 2.2)
    s0, s1 = p.support()
    t = np.linspace(s0 + 1e-3, s1 - 1e-3, 2001)
    h = 1e-5
    assert np.allclose((p.displacement(t + h) - p.displacement(t - h)) / (2 * h), p.velocity(t), atol=1e-8)
    assert np.allclose((p.velocity(t + h) - p.velocity(t - h)) / (2 * h), p.acceleration(t), atol=1e-6)


def test_ground_returns_to_rest_after_rickers_and_cosine_but_not_after_sine():
    for cls in (RickerSymmetric, RickerAntisymmetric, OneCosine):
        p = cls(3.0, 1.1, 4.0)
        end = p.support()[1]
        assert abs(p.velocity(end + 5)) < 1e-15 and abs(p.displacement(end + 5)) < 1e-14
    p = OneSine(3.0, 1.1, 0.0)
    # one-sine: v returns to 0, permanent displacement a_p T_p^2 / (2 pi)
    assert p.velocity(10.0) == pytest.approx(0.0, abs=1e-15)
    assert p.displacement(10.0) == pytest.approx(3.0 * 1.1**2 / (2 * math.pi), rel=1e-13)


@pytest.mark.parametrize("cls,order", [(RickerSymmetric, 2), (RickerAntisymmetric, 3)])
@pytest.mark.parametrize("T_p", [0.25, 1.0, 4.0])
def test_fourier_peak_period_is_T_p(cls, order, T_p):
    p = cls(2.0, T_p)
    assert gaussian_derivative_peak_period(order, p.sigma) == pytest.approx(T_p, rel=1e-14)
    # numerical spectrum of the sampled (truncated) pulse, zero padded for a fine frequency grid
    dt = T_p / 200
    r = p.sampled(dt)
    nfft = 2**20
    spec = np.abs(np.fft.rfft(r.acc, nfft)) * dt
    omega = 2 * np.pi * np.fft.rfftfreq(nfft, dt)
    k = np.argmax(spec)
    # parabolic interpolation of the peak
    y0, y1, y2 = spec[k - 1 : k + 2]
    k_peak = k + 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2)
    T_num = 2 * np.pi / (k_peak * (omega[1] - omega[0]))
    assert T_num == pytest.approx(T_p, rel=1e-5)
    # and the closed-form amplitude matches the numerical one
    sel = slice(1, np.searchsorted(omega, 4 * p.omega_p))
    assert np.allclose(spec[sel], p.fourier_amplitude(omega[sel]), rtol=0, atol=1e-9 * spec.max())
    w = np.linspace(0.2, 3.0, 2001) * p.omega_p
    assert 2 * np.pi / w[np.argmax(p.fourier_amplitude(w))] == pytest.approx(T_p, rel=2e-3)


@pytest.mark.parametrize("cls", ALL)
def test_sampled_record(cls):
    p = cls(0.5 * G, 0.4, 1.5)
    r = p.sampled(0.01, t_end=3.0)
    assert r.dt == 0.01 and r.t_start == 0.0 and r.npts == 301
    assert np.array_equal(r.acc, p.acceleration(r.times))
    assert r.pga_g == pytest.approx(0.5, rel=1e-3)
    # a pulse that starts before 0 is sampled from its start
    q = RickerSymmetric(1.0, 1.0, 1.0)
    rq = q.sampled(0.05)
    assert rq.t_start == pytest.approx(-2.0) and rq.times[-1] == pytest.approx(4.0)
    with pytest.raises(RockcliInputError):
        p.sampled(0.0)
    with pytest.raises(RockcliInputError):
        p.sampled(0.01, t_end=-5.0)


@pytest.mark.parametrize("bad", [dict(a_p=float("nan"), T_p=1.0), dict(a_p=1.0, T_p=0.0), dict(a_p=1.0, T_p=-2.0),
                                 dict(a_p=1.0, T_p=float("inf")), dict(a_p="x", T_p=1.0), dict(a_p=1.0, T_p=1.0, t0=float("nan"))])
@pytest.mark.parametrize("cls", ALL)
def test_invalid_parameters(cls, bad):
    with pytest.raises(RockcliInputError):
        cls(**bad)


def test_make_pulse_and_shapes():
    for name, cls in PULSE_SHAPES.items():
        p = make_pulse(name.upper(), 1.0, 2.0, 0.5)
        assert type(p) is cls and p.shape == name and p.t0 == 0.5
    with pytest.raises(RockcliInputError, match="unknown pulse shape"):
        make_pulse("gabor", 1.0, 1.0)


def test_parse_pulse_spec():
    p = parse_pulse_spec("ricker-sym:ap=0.3,Tp=0.6")
    assert isinstance(p, RickerSymmetric)
    assert p.a_p == pytest.approx(0.3 * G) and p.T_p == 0.6 and p.t0 == pytest.approx(1.8)
    q = parse_pulse_spec(" Sine : AP=-0.25 , tp=2, T0=1.5 ")
    assert isinstance(q, OneSine) and q.a_p == pytest.approx(-0.25 * G) and q.t0 == 1.5
    for cls in ALL:
        r = cls(1.234, 0.77, 2.5)
        assert parse_pulse_spec(r.spec()) == r  # round trip


@pytest.mark.parametrize(
    "spec,match",
    [
        ("gabor:ap=1,Tp=1", "unknown pulse shape"),
        ("sine:ap=1,Tp=1,vp=2", "unknown parameter 'vp'"),
        ("sine:ap=1,Tp", "unknown parameter"),
        ("cosine:Tp=1", "missing ap"),
        ("ricker-anti:ap=0.2", "missing Tp"),
        ("ricker-anti", "missing ap and Tp"),
        ("sine:ap=abc,Tp=1", "not a number"),
        ("sine:ap=0.1,Tp=0", "Tp must be > 0"),
        ("sine:ap=0.1,Tp=-1", "Tp must be > 0"),
        ("sine:ap=0.1,Tp=1,ap=2", "given twice"),
        ("sine:ap=nan,Tp=1", "finite"),
    ],
)
def test_parse_pulse_spec_errors(spec, match):
    with pytest.raises(RockcliInputError, match=match) as info:
        parse_pulse_spec(spec)
    assert "\n" not in str(info.value)


def test_one_time_gives_the_bits_of_the_general_path():
    """``acceleration(t)`` for one float takes a shortcut (no arrays; the slow references call it ~10^5
    times per scene): the same value, bit for bit, as the general path on a 0-d array, at 40,000 random
    times in and around the support of 80 random pulses of every shape, and at the support's ends and
    the floats beside them."""
    rng = np.random.default_rng(25)
    shapes = list(PULSE_SHAPES)
    for i in range(80):
        p = make_pulse(shapes[i % 4], rng.uniform(-30.0, 30.0), rng.uniform(0.05, 5.0), rng.uniform(0.0, 3.0))
        lo, hi = p.support()
        ends = [lo, hi, np.nextafter(lo, -np.inf), np.nextafter(lo, np.inf), np.nextafter(hi, -np.inf),
                np.nextafter(hi, np.inf)]
        for t in np.concatenate([rng.uniform(lo - 1.0, hi + 1.0, 500), ends]):
            general = p.acceleration(np.asarray(t))  # a 0-d array: the general path
            assert isinstance(general, float)
            for one in (float(t), np.float64(t)):
                fast = p.acceleration(one)
                assert type(fast) is float and fast == general and math.copysign(1, fast) == math.copysign(1, general)
    assert p.acceleration(hi + 1.0) == 0.0 and p.acceleration(lo - 1.0) == 0.0
