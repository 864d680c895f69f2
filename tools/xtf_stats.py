#!/usr/bin/python3
"""xtf_stats.py: the image statistics used to judge sidescan realism, per channel, for any XTF.

Reads one or more XTF files with its own reader (the byte layouts of docs/formats.md §1:
the 1024-byte file header with its CHANINFO blocks, then packets that start with magic 0xFACE
and carry their own length; sonar packets, HeaderType 0, are a 256-byte ping header then per
channel a 64-byte channel header and NumSamples samples). Other packet types are skipped.
Samples are decoded from CHANINFO.SampleFormat (0 = unsigned of BytesPerSample, 1 = IBM float32,
2 = 32-bit, 3 = 16-bit, 5 = IEEE float32, 8 = 8-bit; integer formats read as unsigned envelope
values, as pyxtf and the Sea Scan recorder do). Port channels (TypeOfChannel 1) are stored far
range first (spec X41 §2.3.1) and are reversed, so every channel below is nearest sample first.

Definitions (P pings x N samples per channel; sample k at slant range r_k = (k + 0.5)·dr,
dr = SlantRange / N; v the stored sample value, A = v its amplitude, I = v² its intensity; the
samples are taken as envelope amplitudes, so a fully developed speckle gives Rayleigh A and
exponential I):

  seabed region   samples with r_k >= 1.2 x h95 (h95: 95th percentile over pings of the header's
                  SensorPrimaryAltitude; where that is 0, the first sample whose 9-sample running
                  mean exceeds half the ping's median, median over pings) and r_k < SlantRange.
                  All statistics but the saturated fraction and the level profile use only it.
  TVG             a channel whose ping headers set ProcessingFlags bit 4 (TVG) is taken as stored
                  (both the real file and sonarloop's set it). A channel without it is
                  compensated with the area-scattering law, I·(r/r_ref)³ (30 log r, r_ref the
                  last sample's range), and the report says so ("tvg": "compensated 30 log r").
  range profile   M(k) = mean over pings of I(p, k).
  level profile   10 log10(M(k) / I_fs), I_fs = full scale² (65535² for 16-bit, 255² for 8-bit;
                  float: 1), dB re full scale, per range bin; `level_db` is 10 log10 of the mean
                  of M over the seabed region, `level_slope_db_per_10m` the least-squares slope of
                  the level profile over the seabed region, `level_span_db` the max - min of the
                  profile averaged in 8 equal range bands of the seabed region.
  normalised      J(p, k) = I(p, k) / M(k): intensity with the range trend removed.
  moment ratio    <I²>/<I>² in windows of 8 pings x 8 samples (non-overlapping, tiling the
                  seabed region), the mean over windows; windows holding a saturated or a zero
                  mean sample are left out. 2 for fully developed speckle (an exponential
                  intensity; the 64-sample estimator's own bias is -3 % for independent samples),
                  1 for a constant, > 2 for texture or clutter within a window.
  amplitude CV    std(A)/mean(A) in the same windows, mean over windows; sqrt(4/pi - 1) = 0.523
                  for Rayleigh amplitudes.
  full scale      255 (SampleFormat 8, or 0 with 1 byte), 32767 (SampleFormat 3, X41's int16:
                  the samples are read unsigned, so a value above 32767, negative to a signed
                  reader, counts as saturated too), 65535 (SampleFormat 0 with 2 bytes), 2^32 - 1
                  (32-bit integers); float samples have none (1 is taken as the reference).
  saturated       fraction of samples at or above full scale: of all samples (every range,
                  the transmit pulse and water column included) and of the seabed region.
  shadow/highlight  J averaged over 4 pings x 4 samples (box, non-overlapping), its 1st and 99th
                  percentiles in dB re its median: shadow_db = 10 log10(P1/P50),
                  highlight_db = 10 log10(P99/P50); also the 5th and 95th percentiles.
  correlation lengths  of the mean-removed intensity Z = I / <I>_16x16 - 1 (<I>_16x16 the mean
                  over the 16 pings x 16 samples box centred on the sample, shrunk at the edges
                  of the seabed region: it removes the range trend and the scene's large scale,
                  leaving speckle and fine texture): along track, the autocorrelation over
                  pings of each range bin's series, averaged over the seabed bins; across track,
                  over samples of each ping's seabed part, averaged over pings (both unbiased,
                  normalised to 1 at lag 0). The length is the first lag where it falls below
                  1/e, linearly interpolated between lags, in pings and in samples; in metres
                  with the ping spacing (mean SensorSpeed x mean ping interval) and dr.
  median amplitude  the median of A over the seabed region, in % of full scale.

Usage examples:
  /usr/bin/python3 tools/xtf_stats.py tests/data/xtf/scotsman-iver2.xtf
  /usr/bin/python3 tools/xtf_stats.py real.xtf out/render/pings.xtf --json
  /usr/bin/python3 tools/xtf_stats.py real.xtf sim.xtf --plots docs/realism --label real --label sim

Exit status: 0 on success, 1 on a file that cannot be read as XTF (the message names the file and
the byte offset), 2 on bad arguments.
"""

import argparse
import json
import math
import os
import struct
import sys

import numpy as np

FILE_HEADER_BYTES = 1024
CHANINFO_BYTES = 128
CHANINFO_FIRST_BLOCK = 6  # CHANINFOs in the 1024-byte file header
CHANINFO_PER_EXTRA_BLOCK = 8  # each further 1024-byte block of the header holds 8
PING_HEADER_BYTES = 256
CHAN_HEADER_BYTES = 64
PACKET_START_BYTES = 14
MAGIC = 0xFACE
FILE_FORMAT = 0x7B
HEADER_SONAR = 0
CHANNEL_PORT, CHANNEL_STBD = 1, 2
PROCESSING_TVG = 4

# statistics parameters (module docstring)
SEABED_ALTITUDE_FACTOR = 1.2
ALTITUDE_PERCENTILE = 95
SPECKLE_WINDOW = (8, 8)  # pings, samples
LOCAL_MEAN_WINDOW = (4, 4)
SHADOW_PCT, HIGHLIGHT_PCT = 1.0, 99.0
LEVEL_BANDS = 8
DETREND_WINDOW = (16, 16)  # pings, samples: the local mean removed before the autocorrelation
KNOTS_TO_M_S = 1852.0 / 3600.0


class XtfError(Exception):
    """A file that is not XTF, or is truncated or corrupt."""


def ibm_to_float(raw):
    """IBM System/360 single-precision floats (uint32 array, already byte-swapped) to float64."""
    raw = raw.astype(np.uint64)
    sign = np.where(raw >> 31, -1.0, 1.0)
    exponent = ((raw >> 24) & 0x7F).astype(np.int64) - 64
    mantissa = (raw & 0x00FFFFFF).astype(np.float64) / float(1 << 24)
    return sign * mantissa * np.power(16.0, exponent)


def sample_decoding(info):
    """(numpy dtype, full scale or None, description) of a CHANINFO's samples."""
    fmt, nbytes = info["sample_format"], info["bytes_per_sample"]
    if fmt == 5:
        return np.dtype("<f4"), None, "float32"
    if fmt == 1:
        return np.dtype("<u4"), None, "ibm_float32"
    if fmt == 8 or (fmt == 0 and nbytes == 1):
        return np.dtype("u1"), 255, "uint8"
    if fmt == 3:
        # X41's int16: envelope values 0 .. 32767 (read unsigned; a value above 32767 would be
        # negative to a reader that takes the format as signed, and is counted as such)
        return np.dtype("<u2"), 32767, "int16"
    if fmt == 0 and nbytes == 2:
        return np.dtype("<u2"), 65535, "uint16"
    if fmt == 2 or (fmt == 0 and nbytes == 4):
        return np.dtype("<u4"), 4294967295, "uint32"
    raise XtfError(f"SampleFormat {fmt} with BytesPerSample {nbytes} is not supported")


def read_xtf(path):
    """Reads an XTF file: its header fields and, per sonar channel, the samples (pings x N,
    nearest first) and per-ping fields. Raises XtfError naming the byte offset of a problem."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < FILE_HEADER_BYTES:
        raise XtfError(f"{len(data)} bytes, shorter than the 1024-byte XTF file header")
    if data[0] != FILE_FORMAT:
        raise XtfError(f"byte 0 (FileFormat) is 0x{data[0]:02X}, not 0x7B: not an XTF file")

    def text(off, n):
        return data[off:off + n].split(b"\0", 1)[0].decode("latin-1").strip()

    n_sonar, n_bathy = struct.unpack_from("<HH", data, 166)
    n_snippet, n_forward = data[170], data[171]
    (n_echo,) = struct.unpack_from("<H", data, 172)
    n_interf = data[174]
    n_chan = n_sonar + n_bathy + n_snippet + n_forward + n_echo + n_interf
    extra = max(0, n_chan - CHANINFO_FIRST_BLOCK)
    header_bytes = FILE_HEADER_BYTES * (1 + -(-extra // CHANINFO_PER_EXTRA_BLOCK))
    if len(data) < header_bytes:
        raise XtfError(f"{n_chan} channels need a {header_bytes}-byte header; the file has "
                       f"{len(data)} bytes")
    header = {
        "recording_program": text(2, 8), "program_version": text(10, 8),
        "sonar_name": text(18, 16), "sonar_type": struct.unpack_from("<H", data, 34)[0],
        "note": text(36, 64), "nav_units": struct.unpack_from("<H", data, 164)[0],
        "sonar_channels": n_sonar, "bathymetry_channels": n_bathy, "header_bytes": header_bytes,
    }
    chan_infos = []
    for i in range(n_chan):
        if i < CHANINFO_FIRST_BLOCK:
            off = 256 + CHANINFO_BYTES * i
        else:
            off = FILE_HEADER_BYTES + CHANINFO_BYTES * (i - CHANINFO_FIRST_BLOCK)
        ctype, sub, corr, unipolar, nbytes, nominal = struct.unpack_from("<BBHHHI", data, off)
        (volt, freq, horiz, tilt, beam) = struct.unpack_from("<5f", data, off + 28)
        chan_infos.append({
            "type_of_channel": ctype, "sub_channel_number": sub, "correction_flags": corr,
            "uni_polar": unipolar, "bytes_per_sample": nbytes, "nominal_samples": nominal,
            "name": text(off + 12, 16), "volt_scale_v": volt, "frequency": freq,
            "horiz_beam_angle_deg": horiz, "tilt_angle_deg": tilt, "beam_width_deg": beam,
            "sample_format": data[off + 74],
        })
    sonar_infos = [c for c in chan_infos if c["type_of_channel"] in (0, CHANNEL_PORT, CHANNEL_STBD)]
    if len(sonar_infos) < n_sonar:
        raise XtfError(f"the header announces {n_sonar} sonar channels but has "
                       f"{len(sonar_infos)} sonar CHANINFO entries")
    sonar_infos = sonar_infos[:n_sonar]
    for info in sonar_infos:
        if info["bytes_per_sample"] not in (1, 2, 4):
            raise XtfError(f"CHANINFO '{info['name']}' has BytesPerSample "
                           f"{info['bytes_per_sample']}, not 1, 2 or 4")
        info["dtype"], info["full_scale"], info["sample_type"] = sample_decoding(info)

    channels = [{"info": info, "lines": [], "slant_range_m": [], "flags": [],
                 "frequency_khz": [], "seconds_per_ping": []} for info in sonar_infos]
    pings = {"time_s": [], "altitude_m": [], "speed_kn": [], "depth_m": [], "ping_number": []}
    packet_types = {}
    off = header_bytes
    while off < len(data):
        if len(data) - off < PACKET_START_BYTES:
            raise XtfError(f"truncated packet start at byte {off}")
        magic, htype, _sub, nchans = struct.unpack_from("<HBBH", data, off)
        (nbytes,) = struct.unpack_from("<I", data, off + 10)
        if magic != MAGIC:
            raise XtfError(f"no packet magic 0xFACE at byte {off} (found 0x{magic:04X})")
        if nbytes < PACKET_START_BYTES:
            raise XtfError(f"packet at byte {off} claims {nbytes} bytes")
        if off + nbytes > len(data):
            raise XtfError(f"packet at byte {off} claims {nbytes} bytes, only "
                           f"{len(data) - off} remain (truncated file)")
        packet_types[htype] = packet_types.get(htype, 0) + 1
        if htype == HEADER_SONAR:
            read_sonar_packet(data, off, nbytes, nchans, channels, pings)
        off += nbytes
    if not pings["time_s"]:
        raise XtfError("no sonar ping packets (HeaderType 0)")
    for ch in channels:
        lengths = {len(line) for line in ch["lines"]}
        if len(ch["lines"]) != len(pings["time_s"]) or len(lengths) != 1:
            raise XtfError(f"channel '{ch['info']['name']}' is not in every ping with the same "
                           f"sample count ({len(ch['lines'])} of {len(pings['time_s'])} pings, "
                           f"counts {sorted(lengths)})")
        ch["samples"] = np.vstack(ch.pop("lines"))
    header["packet_types"] = {str(k): v for k, v in sorted(packet_types.items())}
    return {"header": header, "channels": channels,
            "pings": {k: np.asarray(v, dtype=float) for k, v in pings.items()}}


def read_sonar_packet(data, off, nbytes, nchans, channels, pings):
    end = off + nbytes
    if nbytes < PING_HEADER_BYTES:
        raise XtfError(f"sonar packet at byte {off} is {nbytes} bytes, under its 256-byte header")
    year, month, day, hour, minute, second, hsec = struct.unpack_from("<HBBBBBB", data, off + 14)
    (jday,) = struct.unpack_from("<H", data, off + 22)
    (ping_number,) = struct.unpack_from("<I", data, off + 28)
    (speed_kn,) = struct.unpack_from("<f", data, off + 152)
    depth_m, altitude_m = struct.unpack_from("<ff", data, off + 192)
    # seconds since the start of the year: enough for intervals within a recording
    pings["time_s"].append(((jday if jday else day) * 24 + hour) * 3600.0 + minute * 60 + second
                           + hsec / 100.0)
    pings["altitude_m"].append(altitude_m)
    pings["speed_kn"].append(speed_kn)
    pings["depth_m"].append(depth_m)
    pings["ping_number"].append(ping_number)
    pos = off + PING_HEADER_BYTES
    for i in range(nchans):
        if pos + CHAN_HEADER_BYTES > end:
            raise XtfError(f"channel header {i} of the sonar packet at byte {off} runs past it")
        (number,) = struct.unpack_from("<H", data, pos)
        slant, _ground, _delay, _duration, spp = struct.unpack_from("<5f", data, pos + 4)
        flags, freq_khz = struct.unpack_from("<HH", data, pos + 24)
        (nsamples,) = struct.unpack_from("<I", data, pos + 42)
        # ChannelNumber indexes the sonar CHANINFOs; fall back on the block's position
        index = number if number < len(channels) else i
        if index >= len(channels):
            raise XtfError(f"sonar packet at byte {off} has channel {number}, the header "
                           f"describes {len(channels)} sonar channels")
        ch = channels[index]
        info = ch["info"]
        nb = nsamples * info["bytes_per_sample"]
        pos += CHAN_HEADER_BYTES
        if pos + nb > end:
            raise XtfError(f"channel {number} of the sonar packet at byte {off}: {nsamples} "
                           f"samples run past the packet's end")
        values = np.frombuffer(data, dtype=info["dtype"], count=nsamples, offset=pos)
        if info["sample_type"] == "ibm_float32":
            values = ibm_to_float(values)
        values = values.astype(np.float64)
        if info["type_of_channel"] == CHANNEL_PORT:
            values = values[::-1]
        ch["lines"].append(values)
        ch["slant_range_m"].append(slant)
        ch["flags"].append(flags)
        ch["frequency_khz"].append(freq_khz)
        ch["seconds_per_ping"].append(spp)
        pos += nb


# ---------------------------------------------------------------------------------------------
# statistics


def seabed_start(samples, altitude_m, dr):
    """First sample index of the seabed region (module docstring)."""
    alt = altitude_m[altitude_m > 0]
    if alt.size > 0:
        h = float(np.percentile(alt, ALTITUDE_PERCENTILE))
    else:
        firsts = []
        kernel = np.ones(9) / 9.0
        for line in samples:
            run = np.convolve(line, kernel, mode="same")
            above = np.nonzero(run > 0.5 * np.median(line))[0]
            firsts.append(above[0] if above.size else 0)
        h = (float(np.median(firsts)) + 0.5) * dr
    return min(samples.shape[1] - 16, int(math.ceil(SEABED_ALTITUDE_FACTOR * h / dr - 0.5))), h


def tiles(a, wp, ws):
    """a cropped to whole windows and reshaped to (n_p, n_s, wp, ws)."""
    p, s = (a.shape[0] // wp) * wp, (a.shape[1] // ws) * ws
    return a[:p, :s].reshape(p // wp, wp, s // ws, ws).swapaxes(1, 2)


def box_mean(a, wp, ws):
    """Mean of a over the wp x ws box centred on each element (the box shrinks at the edges)."""
    def along(x, w, axis):
        x = np.moveaxis(x, axis, -1)
        c = np.concatenate([np.zeros(x.shape[:-1] + (1,)), np.cumsum(x, axis=-1)], axis=-1)
        n = x.shape[-1]
        lo = np.clip(np.arange(n) - w // 2, 0, n)
        hi = np.clip(np.arange(n) - w // 2 + w, 0, n)
        return np.moveaxis((c[..., hi] - c[..., lo]) / (hi - lo), -1, axis)
    return along(along(a, wp, 0), ws, 1)


def correlation_length(acf):
    """First lag (interpolated) where a normalised autocorrelation falls below 1/e."""
    target = 1.0 / math.e
    for lag in range(1, len(acf)):
        if acf[lag] < target:
            a0, a1 = acf[lag - 1], acf[lag]
            return lag - 1 + (a0 - target) / (a0 - a1)
    return float("nan")


def autocorrelation(x, axis, max_lag):
    """Mean over the other axis of the unbiased autocorrelation of x along `axis` (lags
    0..max_lag), normalised to 1 at lag 0."""
    x = np.moveaxis(x, axis, -1)
    n = x.shape[-1]
    size = 1 << int(math.ceil(math.log2(2 * n)))
    spec = np.fft.rfft(x, size, axis=-1)
    acov = np.fft.irfft(spec * np.conj(spec), size, axis=-1)[..., :max_lag + 1]
    acov = acov.mean(axis=tuple(range(acov.ndim - 1))) / (n - np.arange(max_lag + 1))
    return acov / acov[0]


def channel_stats(ch, pings):
    info = ch["info"]
    samples = ch["samples"]
    n_pings, n = samples.shape
    slant = float(np.median(ch["slant_range_m"]))
    dr = slant / n
    r = (np.arange(n) + 0.5) * dr
    full_scale = info["full_scale"]
    intensity = samples ** 2
    tvg_applied = all(int(f) & PROCESSING_TVG for f in ch["flags"])
    if not tvg_applied:
        intensity = intensity * (r / r[-1]) ** 3
    k0, h95 = seabed_start(samples, pings["altitude_m"], dr)
    sea_i = intensity[:, k0:]
    sea_a = samples[:, k0:]

    profile = intensity.mean(axis=0)
    i_fs = float(full_scale) ** 2 if full_scale else 1.0
    with np.errstate(divide="ignore"):
        level_profile_db = 10.0 * np.log10(profile / i_fs)
    sea_profile = profile[k0:]
    bands = np.array_split(sea_profile, LEVEL_BANDS)
    band_db = 10.0 * np.log10(np.array([b.mean() for b in bands]) / i_fs)
    slope = np.polyfit(r[k0:], 10.0 * np.log10(np.maximum(sea_profile, 1e-30) / i_fs), 1)[0]

    saturated = float(np.mean(samples >= full_scale)) if full_scale else 0.0
    saturated_seabed = float(np.mean(sea_a >= full_scale)) if full_scale else 0.0

    # speckle windows
    wi = tiles(sea_i, *SPECKLE_WINDOW).reshape(-1, SPECKLE_WINDOW[0] * SPECKLE_WINDOW[1])
    wa = tiles(sea_a, *SPECKLE_WINDOW).reshape(-1, SPECKLE_WINDOW[0] * SPECKLE_WINDOW[1])
    keep = wi.mean(axis=1) > 0
    if full_scale:
        keep &= wa.max(axis=1) < full_scale
    wi, wa = wi[keep], wa[keep]
    moment_ratio = float(np.mean((wi ** 2).mean(axis=1) / wi.mean(axis=1) ** 2))
    amp_cv = float(np.mean(wa.std(axis=1) / wa.mean(axis=1)))

    # range-normalised intensity, local means and percentiles
    m = np.where(sea_profile > 0, sea_profile, 1.0)
    j = sea_i / m
    local = tiles(j, *LOCAL_MEAN_WINDOW).mean(axis=(2, 3)).ravel()
    p1, p5, p50, p95, p99 = np.percentile(local, [SHADOW_PCT, 5, 50, 95, HIGHLIGHT_PCT])

    def db(x):
        return float(10.0 * math.log10(max(x, 1e-30) / p50))

    # correlation lengths of the intensity with its local mean removed
    z = sea_i / np.maximum(box_mean(sea_i, *DETREND_WINDOW), 1e-30) - 1.0
    acf_along = autocorrelation(z, 0, min(32, n_pings // 4))
    acf_across = autocorrelation(z, 1, min(64, z.shape[1] // 4))
    l_along = correlation_length(acf_along)
    l_across = correlation_length(acf_across)
    t = pings["time_s"]
    # the mean interval: the header's time has 1/100 s steps
    ping_interval = float((t[-1] - t[0]) / (n_pings - 1)) if n_pings > 1 else float("nan")
    speed = float(np.mean(pings["speed_kn"])) * KNOTS_TO_M_S
    ping_spacing = speed * ping_interval

    return {
        "name": info["name"], "type_of_channel": info["type_of_channel"],
        "pings": n_pings, "samples": n, "nominal_samples": info["nominal_samples"],
        "sample_type": info["sample_type"], "bytes_per_sample": info["bytes_per_sample"],
        "sample_format": info["sample_format"], "frequency_khz": info["frequency"],
        "horiz_beam_angle_deg": info["horiz_beam_angle_deg"],
        "beam_width_deg": info["beam_width_deg"], "tilt_angle_deg": info["tilt_angle_deg"],
        "slant_range_m": slant, "bin_m": dr,
        "ping_interval_s": ping_interval, "seconds_per_ping_field": float(
            np.median(ch["seconds_per_ping"])), "speed_m_s": speed, "ping_spacing_m": ping_spacing,
        "altitude_p95_m": h95, "altitude_median_m": float(np.median(pings["altitude_m"])),
        "seabed_start_m": k0 * dr,
        "tvg": "as stored (ProcessingFlags TVG)" if tvg_applied else "compensated 30 log r",
        "moment_ratio": moment_ratio, "amplitude_cv": amp_cv,
        "saturated_fraction": saturated, "saturated_seabed_fraction": saturated_seabed,
        "max_sample": float(samples.max()),
        "median_amplitude_pct_fs": float(np.median(sea_a) / full_scale * 100) if full_scale
        else float(np.median(sea_a)),
        "shadow_db": db(p1), "p5_db": db(p5), "p95_db": db(p95), "highlight_db": db(p99),
        "level_db": float(10.0 * math.log10(sea_profile.mean() / i_fs)),
        "level_slope_db_per_10m": float(slope * 10.0),
        "level_span_db": float(band_db.max() - band_db.min()),
        "level_bands_db": [float(b) for b in band_db],
        "corr_along_pings": l_along, "corr_across_samples": l_across,
        "corr_along_m": l_along * ping_spacing, "corr_across_m": l_across * dr,
        # for the plots
        "_range_m": r, "_level_profile_db": level_profile_db, "_k0": k0,
        "_norm_amplitude": np.sqrt(j).ravel(), "_local_db": 10 * np.log10(
            np.maximum(local, 1e-30) / p50), "_acf_along": acf_along, "_acf_across": acf_across,
    }


# ---------------------------------------------------------------------------------------------
# output

TABLE_ROWS = [
    ("pings", "pings", "{:.0f}"), ("samples", "samples per ping", "{:.0f}"),
    ("sample_type", "sample type", "{}"), ("frequency_khz", "frequency (kHz)", "{:.0f}"),
    ("slant_range_m", "slant range (m)", "{:.2f}"),
    ("ping_interval_s", "ping interval (s)", "{:.3f}"),
    ("ping_spacing_m", "ping spacing (m)", "{:.3f}"),
    ("altitude_median_m", "altitude, median (m)", "{:.2f}"),
    ("seabed_start_m", "seabed region from (m)", "{:.2f}"),
    ("moment_ratio", "<I^2>/<I>^2, 8x8", "{:.3f}"), ("amplitude_cv", "amplitude CV, 8x8", "{:.3f}"),
    ("saturated_fraction", "saturated fraction, all", "{:.4f}"),
    ("saturated_seabed_fraction", "saturated fraction, seabed", "{:.4f}"),
    ("median_amplitude_pct_fs", "median amplitude (% FS)", "{:.2f}"),
    ("level_db", "mean level (dB re FS)", "{:.2f}"),
    ("level_slope_db_per_10m", "level slope (dB/10 m)", "{:.2f}"),
    ("level_span_db", "level span, 8 bands (dB)", "{:.2f}"),
    ("shadow_db", "shadow P1 (dB re median)", "{:.2f}"), ("p5_db", "P5 (dB re median)", "{:.2f}"),
    ("p95_db", "P95 (dB re median)", "{:.2f}"),
    ("highlight_db", "highlight P99 (dB re median)", "{:.2f}"),
    ("corr_along_pings", "corr. along track (pings)", "{:.2f}"),
    ("corr_along_m", "corr. along track (m)", "{:.3f}"),
    ("corr_across_samples", "corr. across track (samples)", "{:.2f}"),
    ("corr_across_m", "corr. across track (m)", "{:.3f}"),
]


def public(stats):
    return {k: v for k, v in stats.items() if not k.startswith("_")}


def print_table(results, markdown):
    cols = [(label, c) for label, r in results for c in r["channels"]]
    heads = [f"{label} {c['name'].lower()}" for label, c in cols]
    rows = [[title] + [fmt.format(c[key]) for _, c in cols] for key, title, fmt in TABLE_ROWS]
    if markdown:
        print("| statistic | " + " | ".join(heads) + " |")
        print("|---|" + "---:|" * len(heads))
        for row in rows:
            print("| " + " | ".join(row) + " |")
        return
    widths = [max(len(x) for x in col) for col in zip(["statistic"] + heads, *rows)]
    for row in [["statistic"] + heads] + rows:
        print("  ".join(x.ljust(w) if i == 0 else x.rjust(w) for i, (x, w) in
                        enumerate(zip(row, widths))))


def make_plots(results, out_dir, waterfall):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    os.makedirs(out_dir, exist_ok=True)
    styles = ["-", "--", ":", "-."]
    written = []

    # histograms: normalised amplitude against Rayleigh, and locally averaged intensity (dB)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    a = np.linspace(0, 4, 400)
    axes[0].plot(a, np.pi / 2 * a * np.exp(-np.pi / 4 * a ** 2),
                 "k", lw=0.8, label="Rayleigh (speckle)")
    for i, (label, r) in enumerate(results):
        for c in r["channels"]:
            x = c["_norm_amplitude"]
            x = x / np.mean(x)
            h, e = np.histogram(x, bins=200, range=(0, 4), density=True)
            axes[0].plot(0.5 * (e[1:] + e[:-1]), h, styles[i % 4],
                         label=f"{label} {c['name'].lower()}")
            h, e = np.histogram(c["_local_db"], bins=120, range=(-15, 10), density=True)
            axes[1].semilogy(0.5 * (e[1:] + e[:-1]), np.maximum(h, 1e-5), styles[i % 4],
                             label=f"{label} {c['name'].lower()}")
    axes[0].set_xlabel("amplitude / mean amplitude (range trend removed)")
    axes[0].set_ylim(0, 1.6)  # shadows pile up at 0 beyond
    axes[0].set_ylabel("density")
    axes[0].legend(fontsize=8)
    axes[1].set_xlabel("4x4 mean intensity, dB re median")
    axes[1].set_ylabel("density")
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out_dir, "histograms.png")
    fig.savefig(path, dpi=90)
    plt.close(fig)
    written.append(path)

    fig, ax = plt.subplots(figsize=(8, 4))
    for i, (label, r) in enumerate(results):
        for c in r["channels"]:
            ax.plot(c["_range_m"], c["_level_profile_db"], styles[i % 4], lw=0.8,
                    label=f"{label} {c['name'].lower()}")
        ax.axvline(r["channels"][0]["seabed_start_m"], color="0.6", ls=styles[i % 4], lw=0.6)
    ax.set_xlabel("slant range (m)")
    ax.set_ylabel("mean intensity over pings, dB re full scale")
    ax.set_title("level against range (as stored: TVG applied)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    path = os.path.join(out_dir, "level_vs_range.png")
    fig.savefig(path, dpi=90)
    plt.close(fig)
    written.append(path)

    fig, axes = plt.subplots(1, 2, figsize=(11, 3.6))
    for i, (label, r) in enumerate(results):
        for c in r["channels"]:
            axes[0].plot(c["_acf_along"], styles[i % 4], label=f"{label} {c['name'].lower()}")
            axes[1].plot(c["_acf_across"], styles[i % 4], label=f"{label} {c['name'].lower()}")
    for ax, what in zip(axes, ["along track (pings)", "across track (samples)"]):
        ax.axhline(1 / math.e, color="k", lw=0.6)
        ax.set_xlabel("lag, " + what)
        ax.set_ylabel("autocorrelation of I/<I>16x16 - 1")
        ax.set_xlim(0, 16)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    path = os.path.join(out_dir, "autocorrelation.png")
    fig.savefig(path, dpi=90)
    plt.close(fig)
    written.append(path)

    if waterfall:
        for label, r in results:
            chans = r["_channels_raw"]
            port = [c for c in chans if c["info"]["type_of_channel"] == CHANNEL_PORT]
            stbd = [c for c in chans if c["info"]["type_of_channel"] != CHANNEL_PORT]
            parts = [c["samples"][:, ::-1] for c in port[:1]] + [c["samples"] for c in stbd[:1]]
            img = np.hstack(parts)[::-1]  # last ping at the top
            img = 0.5 * (img[:, 0::2] + img[:, 1::2])  # half width: pairs of samples averaged
            top = np.percentile(img, 99.5)
            grey = np.round(255 * np.clip(img / max(top, 1e-12), 0, 1)).astype(np.uint8)
            path = os.path.join(out_dir, f"waterfall_{label}.png")
            from PIL import Image  # matplotlib's own image library
            Image.fromarray(grey, "L").save(path)
            written.append(path)
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="xtf_stats.py", description=__doc__.split("\n\n")[0],
        epilog="Examples:\n"
        "  /usr/bin/python3 tools/xtf_stats.py tests/data/xtf/scotsman-iver2.xtf\n"
        "  /usr/bin/python3 tools/xtf_stats.py a.xtf b.xtf --json\n"
        "  /usr/bin/python3 tools/xtf_stats.py real.xtf sim.xtf --label real --label sim "
        "--plots docs/realism --waterfall --markdown\n"
        "Every statistic is defined in this script's docstring and in docs/realism.md.",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+", metavar="FILE.xtf")
    parser.add_argument("--json", action="store_true", help="print the statistics as JSON")
    parser.add_argument("--markdown", action="store_true", help="print the table as Markdown")
    parser.add_argument("--label", action="append", default=[],
                        help="a name per file for tables and plots (default: the file's stem)")
    parser.add_argument("--plots", metavar="DIR",
                        help="write histograms.png, level_vs_range.png, autocorrelation.png")
    parser.add_argument("--waterfall", action="store_true",
                        help="with --plots: also waterfall_<label>.png per file: port left, last ping "
                        "at the top, pairs of samples averaged, 8-bit grey scaled to the 99.5th "
                        "percentile")
    args = parser.parse_args(argv)
    if args.label and len(args.label) != len(args.files):
        parser.error(f"{len(args.label)} --label for {len(args.files)} files")
    if args.waterfall and not args.plots:
        parser.error("--waterfall needs --plots DIR")

    results = []
    for i, path in enumerate(args.files):
        label = args.label[i] if args.label else os.path.splitext(os.path.basename(path))[0]
        try:
            xtf = read_xtf(path)
        except OSError as e:
            print(f"xtf_stats.py: {path}: {e.strerror}", file=sys.stderr)
            return 1
        except XtfError as e:
            print(f"xtf_stats.py: {path}: not readable as XTF: {e}", file=sys.stderr)
            return 1
        if not xtf["channels"]:
            print(f"xtf_stats.py: {path}: no sonar channels", file=sys.stderr)
            return 1
        stats = [channel_stats(ch, xtf["pings"]) for ch in xtf["channels"]]
        results.append((label, {"file": path, "header": xtf["header"], "channels": stats,
                                "_channels_raw": xtf["channels"]}))

    if args.plots:
        written = make_plots(results, args.plots, args.waterfall)
        if not args.json:
            for p in written:
                print(f"wrote {p}", file=sys.stderr)
    if args.json:
        out = [{"label": label, "file": r["file"], "header": r["header"],
                "channels": [public(c) for c in r["channels"]]} for label, r in results]
        print(json.dumps(out, indent=1, default=float))
    else:
        print_table(results, args.markdown)
    return 0


if __name__ == "__main__":
    sys.exit(main())
