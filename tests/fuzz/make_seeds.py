#!/usr/bin/env python3
"""Writes the seed corpora of the state and PC2 fuzz targets: tests/fuzz/seeds_state/ and
tests/fuzz/seeds_pc2/, each file with its expected outcome in the folder's expected.txt.

    tests/fuzz/make_seeds.py build/clothsim-headless

The valid files are written by clothsim itself (`simulate --save-state` on the CPU reference in
double and on the GPU in float, both solvers, `--export FILE.pc2`, and a run continued from a
state) on a 3x2 cloth, or derived from them (the older versions 1, 2 and 3), so they are a few hundred bytes the others are copies of them with one thing broken
(cut short, a field out of range, a NaN with its checksum made to match, ...); a header field
out of range needs no more than the header. The GPU state
needs an OpenGL 4.3 context (llvmpipe will do). Rerun it when a format changes, and commit what
it writes; the files a format no longer reads are the ones whose line in expected.txt fails.
"""
import os
import shutil
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))

SCENE = ('{"cloth": {"width": 1, "height": 1, "num_width_points": 3, "num_height_points": 2,\n'
         '           "thickness": 0.0095, "orientation": 0, "pinned": [[0, 0]]}}\n')


def fnv1a(data):
    h = 0xcbf29ce484222325
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return h


def with_checksum(body):
    """A state file's bytes but its last 8, then their FNV-1a: the checksum the reader expects."""
    return body + struct.pack('<Q', fnv1a(body))


def patch(data, offset, fmt, value):
    return data[:offset] + struct.pack(fmt, value) + data[offset + struct.calcsize(fmt):]


def state_header(state):
    """A state's header size by its version: 72 (version 1), 80 (2 and 3), 88 (4)."""
    version = struct.unpack_from('<I', state, 16)[0]
    return 72 if version == 1 else 80 if version <= 3 else 88


def state_stream_offset(state):
    """Where a state's positions start: the header and the two names."""
    scene_len, backend_len = struct.unpack_from('<II', state, 56)
    return state_header(state) + scene_len + backend_len


def as_version_3(state):
    """A version-4 state without solve offsets as version 3 wrote it: the 80-byte header."""
    assert struct.unpack_from('<I', state, 80)[0] == 0, 'no solve offsets'
    return with_checksum(patch(state[:80], 16, '<I', 3) + state[88:-8])


def state_seeds(cpu, gpu, xpbd, fabric, pc2):
    """(file, bytes, outcome, why) for seeds_state/; outcome is 'loads' or 'rejected<TAB>message'."""
    f_pos = state_stream_offset(gpu)   # float positions: 16 bytes per particle
    d_pos = state_stream_offset(cpu)   # double positions: 32 bytes per particle
    d_disp = d_pos + 6 * 32            # the 3x2 cloth's displacements follow its positions
    # Versions 1 and 2: the streams without the version-3 multipliers (their count at offset 68,
    # 16 bytes each in floats), version 1 also without the dt (a 72-byte header); checksummed again.
    v3_gpu = as_version_3(gpu)
    multipliers = struct.unpack_from('<I', v3_gpu, 68)[0] * 16
    older = patch(v3_gpu, 68, '<I', 0)[:len(v3_gpu) - 8 - multipliers]
    v2 = with_checksum(patch(older, 16, '<I', 2))
    v1 = with_checksum(patch(older[:72], 16, '<I', 1) + older[80:])
    # The xpbd state's multipliers (4 doubles per spring) follow its two streams.
    springs = struct.unpack_from('<I', xpbd, 68)[0]
    x_lambda = state_stream_offset(xpbd) + 2 * 6 * 32
    assert springs > 0 and len(xpbd) == x_lambda + springs * 32 + 8, 'the xpbd state carries its multipliers'
    nan = float('nan')
    return [
        ('v4_double_cpu.state', cpu, 'loads', 'simulate --backend cpu --frames 3 --save-state: 3x2, doubles'),
        ('v4_float_gpu.state', gpu, 'loads', 'simulate --backend gpu --frames 3 --save-state: 3x2, floats'),
        ('v3_float_gpu.state', v3_gpu, 'loads', 'the float state as version 3 (80-byte header, no offsets): still read'),
        ('v4_xpbd_double_cpu.state', xpbd, 'loads',
         f'the same, saved under the removed xpbd solver: {springs} springs\' multipliers after the streams'),
        ('v4_fabric_double_cpu.state', fabric, 'loads',
         'simulate --backend cpu --frames 3 --set simulation.solver=fabric --save-state: version 4, with the solve offsets'),
        ('v2_float_gpu.state', v2, 'loads', 'the float state as version 2 (no multipliers): still read'),
        ('v1_float.state', v1, 'loads', 'the float state as version 1 (72-byte header, no dt): still read'),
        ('nan_multiplier.state', with_checksum(patch(xpbd, x_lambda + 32 + 24, '<d', nan)[:-8]),
         'rejected\tthe multiplier of spring 1 has w = nan', 'a NaN multiplier with a matching checksum'),
        ('multipliers_out_of_range.state', patch(xpbd[:88], 68, '<I', 385),
         'rejected\t385 spring multipliers for 6 particles is out of range', 'more than 64 springs a particle'),
        ('truncated_multipliers.state', xpbd[:-16],
         f'rejected\ttruncated ({len(xpbd) - 16} bytes, a 3x2 cloth of 8-byte scalars needs {len(xpbd)})',
         'cut inside the multipliers'),
        ('empty.state', b'', 'rejected\tnot a clothsim state file', 'an empty file'),
        ('foreign_pc2.state', pc2, 'rejected\tnot a clothsim state file', 'a PC2 cache given as a state'),
        ('truncated_header.state', cpu[:60], 'rejected\ttruncated (60 bytes, shorter than the header)',
         'cut inside the header'),
        ('truncated_stream.state', cpu[:-40],
         f'rejected\ttruncated ({len(cpu) - 40} bytes, a 3x2 cloth of 8-byte scalars needs {len(cpu)})',
         'cut inside the displacements'),
        ('trailing_byte.state', gpu + b'\0', 'rejected\thas trailing bytes', 'one byte too many'),
        ('version_5.state', patch(gpu[:88], 16, '<I', 5), 'rejected\tstate file version 5', 'an unknown version'),
        ('scalar_6.state', patch(gpu[:88], 20, '<I', 6), 'rejected\tscalar size 6 bytes', 'neither float nor double'),
        ('grid_4096x4096.state', patch(patch(gpu, 24, '<I', 4096), 28, '<I', 4096),
         f'rejected\ta 4096x4096 cloth of 4-byte scalars needs {f_pos + 2 * 4096 * 4096 * 16 + multipliers + 8}',
         'a legal grid the file is far too short for: refused before 512 MiB are allocated'),
        ('grid_8192x4096.state', patch(patch(gpu[:88], 24, '<I', 8192), 28, '<I', 4096),
         'rejected\tgrid 8192x4096 is out of range', 'more particles than kMaxParticles'),
        ('scene_name_5000.state', patch(gpu[:88], 56, '<I', 5000), 'rejected\tname lengths out of range',
         'a name longer than 4096 bytes'),
        ('checksum_mismatch.state', gpu[:f_pos] + b'\x01' + gpu[f_pos + 1:], 'rejected\tchecksum mismatch',
         'a position byte changed, the checksum not'),
        ('nan_position.state', with_checksum(patch(gpu, f_pos + 16 + 4, '<f', nan)[:-8]),
         'rejected\tthe position of particle 1 has y = nan', 'a NaN with a matching checksum'),
        ('inf_displacement.state', with_checksum(patch(cpu, d_disp + 4 * 32 + 16, '<d', float('inf'))[:-8]),
         'rejected\tthe displacement of particle 4 has z = inf', 'an Inf with a matching checksum'),
        ('negative_time.state', with_checksum(patch(gpu, 48, '<d', -1.0)[:-8]),
         'rejected\tthe simulated time is -1', 'a time < 0 with a matching checksum'),
        ('negative_frame.state', with_checksum(patch(gpu, 40, '<q', -1)[:-8]),
         'rejected\tthe frame is -1', 'a frame < 0 with a matching checksum'),
        ('zero_dt.state', with_checksum(patch(gpu, 72, '<d', 0.0)[:-8]),
         'rejected\tthe substep length is 0 s', 'a dt of 0 with a matching checksum'),
    ]


def pc2_seeds(cache, resumed, state):
    """(file, bytes, outcome, why) for seeds_pc2/."""
    points, samples = struct.unpack_from('<i', cache, 16)[0], struct.unpack_from('<i', cache, 28)[0]
    last = 32 + (samples - 1) * points * 12
    nan = float('nan')
    return [
        ('cpu_6_points_4_samples.pc2', cache, 'loads', 'simulate --backend cpu --frames 3 --export: frames 0-3'),
        ('resumed_every_2.pc2', resumed, 'loads',
         'simulate --load-state (frame 3) --frames 4 --export-every 2: start frame 3, sample rate 2'),
        ('partial_sample_past_the_count.pc2', cache + cache[32:52], 'loads',
         'part of a fifth sample past the count, as while a cache is written'),
        ('no_samples.pc2', patch(cache[:32], 28, '<i', 0), 'loads', 'a header with no samples yet'),
        ('empty.pc2', b'', 'rejected\tnot a PC2 file', 'an empty file'),
        ('foreign_state.pc2', state, 'rejected\tnot a PC2 file', 'a state file given as a cache'),
        ('truncated_header.pc2', cache[:20], 'rejected\tnot a PC2 file', 'cut inside the header'),
        ('truncated_sample.pc2', cache[:-1], 'rejected\ttruncated: the header claims 6 points x 4 samples',
         'one byte short of the last sample'),
        ('points_2_30.pc2', patch(patch(cache[:100], 16, '<i', 1 << 30), 28, '<i', 1),
         'rejected\ttruncated: the header claims 1073741824 points x 1 samples',
         'a 12 GiB sample claimed by a 100-byte file: refused before allocating'),
        ('negative_points.pc2', patch(cache[:32], 16, '<i', -5), 'rejected\tcorrupted header (-5 points',
         'a negative count'),
        ('nan_start_frame.pc2', patch(cache[:32], 20, '<f', nan), 'rejected\tcorrupted header (start frame nan',
         'a start frame that is NaN'),
        ('inf_sample_rate.pc2', patch(cache[:32], 24, '<f', float('inf')), 'rejected\tsample rate inf',
         'a sample rate that is Inf'),
        ('nan_in_last_sample.pc2', patch(cache, last + 5 * 12 + 8, '<f', nan),
         'rejected\tsample 3: point 5 has z = nan', 'a NaN in the last sample'),
    ]


def write_corpus(folder, seeds, what):
    os.makedirs(folder, exist_ok=True)
    for name in os.listdir(folder):
        os.remove(os.path.join(folder, name))
    lines = [f'# Seeds of the {what} fuzz target, written by tests/fuzz/make_seeds.py (tests/fuzz/README.md):',
             '# file<TAB>loads, or file<TAB>rejected<TAB>substring of the error message.']
    for name, data, outcome, why in seeds:
        with open(os.path.join(folder, name), 'wb') as f:
            f.write(data)
        lines += [f'# {why}', f'{name}\t{outcome}']
    with open(os.path.join(folder, 'expected.txt'), 'w') as f:
        f.write('\n'.join(lines) + '\n')


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    clothsim = os.path.abspath(sys.argv[1])
    # A state of the removed xpbd solver (its springs' multipliers after the streams), kept from
    # the corpus as it was last generated: files users saved then must still read.
    with open(os.path.join(HERE, 'seeds_state', 'v4_xpbd_double_cpu.state'), 'rb') as f:
        xpbd = f.read()
    tmp = tempfile.mkdtemp()
    try:
        def run(*args):
            subprocess.run([clothsim, 'simulate', 'seed_cloth.json', *args], cwd=tmp, check=True,
                           stdout=subprocess.DEVNULL)

        def read(name):
            with open(os.path.join(tmp, name), 'rb') as f:
                return f.read()

        with open(os.path.join(tmp, 'seed_cloth.json'), 'w') as f:
            f.write(SCENE)
        run('--backend', 'cpu', '--frames', '3', '--save-state', 'cpu.state', '--export', 'cache.pc2')
        run('--backend', 'gpu', '--frames', '3', '--save-state', 'gpu.state')
        run('--backend', 'cpu', '--frames', '3', '--set', 'simulation.solver=fabric', '--save-state', 'fabric.state')
        run('--backend', 'cpu', '--load-state', 'cpu.state', '--frames', '4', '--export-every', '2',
            '--export', 'resumed.pc2')
        cpu, gpu, fabric = read('cpu.state'), read('gpu.state'), read('fabric.state')
        cache, resumed = read('cache.pc2'), read('resumed.pc2')
    finally:
        shutil.rmtree(tmp)
    write_corpus(os.path.join(HERE, 'seeds_state'), state_seeds(cpu, gpu, xpbd, fabric, cache), 'state-file')
    write_corpus(os.path.join(HERE, 'seeds_pc2'), pc2_seeds(cache, resumed, gpu), 'PC2')


if __name__ == '__main__':
    main()
